// WebXR (SPEC I1 with VR controllers): an "Enter VR" button starts an immersive-vr session
// through three.js' renderer.xr. Each controller is a hand of its own: squeeze grabs the
// beam nearest to the controller's grip, moving sends the grip pose (position, and the
// rotation since the grab), releasing the squeeze lets go. Both hands work at once. Each
// controller has its own grip (grips.ts): its A/X button (or thumbstick press) cycles
// firm → axial → ball, shown by a label and the colour of its marker; cycling while
// holding re-grabs with the new grip at once. While in VR, the scene is placed in front of
// the user at working height. An "Enter AR" button, where the device supports
// `immersive-ar`, starts the same with the real world behind: the scene stands on the real
// floor (xr_placement.ts), without its own background, fog and ground; where the device
// has the WebXR hit test (`hit-test`), a reticle shows where the view's ray meets a real
// surface facing up, and select stands the scene's lowest point there (a table).

import * as THREE from 'three';
import { nextGrip, type Grip } from './grips';
import type { Net } from './net';
import type { Stage } from './scene';
import { canvasSprite, type CanvasSprite } from './sprite';
import { bodyPoseDue, bodyPoseMessage } from './xr_body';
import type { Vec3 } from './protocol';
import { facesUp, hitOffset, xrOffset, type XrMode } from './xr_placement';

interface XrHand {
  grip: THREE.Group;
  handId: number;
  held: boolean;
  grabRotation: THREE.Quaternion;
  handedness: string;
  /** How this controller holds a hose (its grip choice). */
  hold: Grip;
  marker: THREE.Mesh<THREE.SphereGeometry, THREE.MeshStandardMaterial>;
  label: CanvasSprite;
  gamepad: Gamepad | null;
  /** Whether the cycling button was down at the last frame (edge detection). */
  buttonDown: boolean;
}

/** Marker colour per grip. */
const GRIP_COLOUR: Record<Grip, number> = { firm: 0xffffff, axial: 0xffd23f, ball: 0xff5fd2 };

/** A small text sprite above a controller, naming its grip. */
function gripSprite(): CanvasSprite {
  const label = canvasSprite(256, 64);
  label.sprite.position.set(0, 0.045, 0);
  label.sprite.scale.set(0.08, 0.02, 1);
  return label;
}

export class XrHands {
  readonly hands: XrHand[] = [];
  readonly button: HTMLButtonElement;
  readonly arButton: HTMLButtonElement;
  private session: XRSession | null = null;
  /** The mode of the session running (null: none). */
  mode: XrMode | null = null;
  private readonly pos = new THREE.Vector3();
  private readonly rot = new THREE.Quaternion();
  /** Base of hand ids (set from the client id so that viewers do not clash). */
  handBase = 1;
  /** Whether the scene has a worker: the headset and controllers then pose him
   *  (xr_body.ts). */
  worker = false;
  /** When the last `worker_pose` was sent [ms]. */
  private lastBodyPose = -Infinity;
  private readonly ahead = new THREE.Vector3();
  /** AR's hit test: requested, running, or not offered by the device or browser (the
   *  scene then stays on the floor); null outside AR. */
  hitTest: 'pending' | 'available' | 'unavailable' | null = null;
  private hitSource: XRHitTestSource | null = null;
  /** Where the view's ray meets a real surface facing up (shown when it does). */
  private readonly reticle: THREE.Mesh;
  /** The surface point the scene stands on in AR (three.js space); null: the floor. */
  private surface: Vec3 | null = null;

  constructor(private readonly stage: Stage, private readonly net: Net, parent: HTMLElement) {
    const xr = stage.renderer.xr;
    xr.enabled = true;
    this.button = document.createElement('button');
    this.button.id = 'enter-vr';
    this.button.textContent = 'VR not available';
    this.button.disabled = true;
    this.arButton = document.createElement('button');
    this.arButton.id = 'enter-ar';
    this.arButton.textContent = 'AR not available';
    this.arButton.disabled = true;
    parent.append(this.button, this.arButton);
    this.reticle = new THREE.Mesh(
      new THREE.RingGeometry(0.04, 0.05, 32).rotateX(-Math.PI / 2),
      new THREE.MeshBasicMaterial({ color: 0x3fb950 }),
    );
    this.reticle.matrixAutoUpdate = false;
    this.reticle.visible = false;
    stage.scene.add(this.reticle);
    void this.checkSupport();
    this.button.onclick = () => void this.toggle('immersive-vr');
    this.arButton.onclick = () => void this.toggle('immersive-ar');
    for (let i = 0; i < 2; i++) {
      const grip = xr.getControllerGrip(i);
      const marker = new THREE.Mesh(
        new THREE.SphereGeometry(0.015, 16, 8),
        new THREE.MeshStandardMaterial({ color: 0xffffff, emissive: 0x333333 }),
      );
      const label = gripSprite();
      grip.add(marker, label.sprite);
      stage.scene.add(grip);
      const hand: XrHand = {
        grip, handId: i + 1, held: false, grabRotation: new THREE.Quaternion(), handedness: '',
        hold: 'firm', marker, label, gamepad: null, buttonDown: false,
      };
      this.showGrip(hand);
      grip.addEventListener('connected', (e) => {
        const data = (e as unknown as { data?: XRInputSource }).data;
        hand.handedness = data?.handedness ?? '';
        hand.gamepad = data?.gamepad ?? null;
      });
      grip.addEventListener('disconnected', () => {
        hand.gamepad = null;
      });
      grip.addEventListener('squeezestart', () => this.grab(hand));
      grip.addEventListener('squeezeend', () => this.release(hand));
      this.hands.push(hand);
    }
  }

  private async checkSupport(): Promise<void> {
    const supports = async (mode: XrMode) => navigator.xr !== undefined && (await navigator.xr.isSessionSupported(mode).catch(() => false));
    const [vr, ar] = [await supports('immersive-vr'), await supports('immersive-ar')];
    this.button.disabled = !vr;
    this.button.textContent = vr ? 'Enter VR' : 'VR not available';
    this.arButton.disabled = !ar;
    this.arButton.textContent = ar ? 'Enter AR' : 'AR not available';
  }

  get inSession(): boolean {
    return this.session !== null;
  }

  private async toggle(mode: XrMode): Promise<void> {
    if (this.session !== null) {
      await this.session.end();
      return;
    }
    if (navigator.xr === undefined) return;
    const optionalFeatures = mode === 'immersive-ar' ? ['local-floor', 'hit-test'] : ['local-floor'];
    const session = await navigator.xr.requestSession(mode, { optionalFeatures });
    this.stage.renderer.xr.setReferenceSpaceType('local-floor');
    await this.stage.renderer.xr.setSession(session);
    this.session = session;
    this.mode = mode;
    const button = mode === 'immersive-ar' ? this.arButton : this.button;
    const word = mode === 'immersive-ar' ? 'AR' : 'VR';
    button.textContent = `Exit ${word}`;
    const backdrop = { background: this.stage.scene.background, fog: this.stage.scene.fog };
    if (mode === 'immersive-ar') this.showBackdrop(false);
    this.place(true);
    if (mode === 'immersive-ar') {
      void this.startHitTest(session);
      session.addEventListener('select', () => {
        if (this.reticle.visible) this.standOn(this.reticle.position.toArray());
      });
    }
    session.addEventListener('end', () => {
      for (const h of this.hands) this.release(h);
      this.hitSource?.cancel();
      this.hitSource = null;
      this.hitTest = null;
      this.surface = null;
      this.reticle.visible = false;
      this.session = null;
      this.mode = null;
      button.textContent = `Enter ${word}`;
      this.stage.scene.background = backdrop.background;
      this.stage.scene.fog = backdrop.fog;
      this.showBackdrop(true);
      this.place(false);
    });
  }

  /** The scene's own backdrop (background, fog, ground) shown or, in AR, left to the
   *  real world. */
  private showBackdrop(on: boolean): void {
    if (!on) {
      this.stage.scene.background = null;
      this.stage.scene.fog = null;
    }
    const ground = this.stage.world.getObjectByName('ground');
    if (ground !== undefined) ground.visible = on;
  }

  /** In a session: where xr_placement.ts puts the scene for its mode; else at the origin. */
  place(inSession: boolean): void {
    const w = this.stage.world;
    w.position.set(0, 0, 0);
    w.updateMatrixWorld(true);
    if (inSession && this.mode !== null) {
      const c = this.stage.toThree([this.stage.centre.x, this.stage.centre.y, this.stage.centre.z]);
      const lowest = new THREE.Box3().setFromObject(w).min.y;
      const low = Number.isFinite(lowest) ? lowest : c.y;
      const onSurface = this.mode === 'immersive-ar' && this.surface !== null;
      w.position.set(...(onSurface && this.surface !== null ? hitOffset([c.x, c.y, c.z], low, this.surface) : xrOffset(this.mode, [c.x, c.y, c.z], low)));
      if (this.mode === 'immersive-ar') this.showBackdrop(false);
    }
    w.updateMatrixWorld(true);
  }

  /** AR: asks for a hit test along the view's ray; a device or browser without it
   *  (NotSupportedError, or an emulator without a synthetic environment) leaves the scene
   *  on the floor. */
  private async startHitTest(session: XRSession): Promise<void> {
    this.hitTest = 'pending';
    try {
      if (session.requestHitTestSource === undefined) throw new Error('no hit test');
      const viewer = await session.requestReferenceSpace('viewer');
      const source = await session.requestHitTestSource({ space: viewer });
      if (this.session !== session || source === undefined) {
        source?.cancel();
        return;
      }
      this.hitSource = source;
      this.hitTest = 'available';
    } catch {
      if (this.session === session) this.hitTest = 'unavailable';
    }
  }

  /** AR: the scene's lowest point onto the real surface at `hit` (three.js space), its
   *  centre above it. */
  standOn(hit: Vec3): void {
    if (this.mode !== 'immersive-ar') return;
    this.surface = hit;
    this.place(true);
  }

  /** The reticle where this frame's first hit on a surface facing up is. */
  private showReticle(): void {
    const frame = this.stage.renderer.xr.getFrame();
    const space = this.stage.renderer.xr.getReferenceSpace();
    this.reticle.visible = false;
    if (this.hitSource === null || frame === null || space === null) return;
    for (const hit of frame.getHitTestResults(this.hitSource)) {
      const pose = hit.getPose(space);
      const q = pose?.transform.orientation;
      if (pose === undefined || q === undefined || !facesUp([q.x, q.y, q.z, q.w])) continue;
      this.reticle.matrix.fromArray(pose.transform.matrix);
      this.reticle.matrix.decompose(this.reticle.position, this.reticle.quaternion, this.reticle.scale);
      this.reticle.visible = true;
      return;
    }
  }

  private grab(h: XrHand): void {
    h.grip.getWorldPosition(this.pos);
    h.grip.getWorldQuaternion(h.grabRotation);
    const position = this.stage.toWorld(this.pos);
    h.held = this.net.send({ type: 'grab', hand_id: this.handBase + h.handId, position, grip: h.hold });
  }

  /** Controller `i`'s next grip (its A/X button); a held hose is re-grabbed with it. */
  cycleGrip(i: number): Grip | null {
    const h = this.hands[i];
    if (h === undefined) return null;
    h.hold = nextGrip(h.hold);
    this.showGrip(h);
    if (h.held) this.grab(h);
    return h.hold;
  }

  /** The controller's marker colour and label show its grip. */
  private showGrip(h: XrHand): void {
    h.marker.material.color.setHex(GRIP_COLOUR[h.hold]);
    const ctx = h.label.canvas.getContext('2d');
    if (ctx === null) return;
    ctx.clearRect(0, 0, 256, 64);
    ctx.fillStyle = 'rgba(13,17,23,0.8)';
    ctx.fillRect(0, 0, 256, 64);
    ctx.fillStyle = `#${GRIP_COLOUR[h.hold].toString(16).padStart(6, '0')}`;
    ctx.font = 'bold 38px sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ctx.fillText(`grip: ${h.hold}`, 128, 34);
    h.label.texture.needsUpdate = true;
  }

  private release(h: XrHand): void {
    if (!h.held) return;
    h.held = false;
    this.net.send({ type: 'release', hand_id: this.handBase + h.handId });
  }

  /** Sends each held controller's pose (once per frame). */
  update(): void {
    this.hands.forEach((h, i) => {
      // A/X (xr-standard button 4) or the thumbstick press (3): next grip, on the press
      const b = h.gamepad?.buttons;
      const down = b !== undefined && ((b[4]?.pressed ?? false) || (b[3]?.pressed ?? false));
      if (down && !h.buttonDown) this.cycleGrip(i);
      h.buttonDown = down;
    });
    this.sendBodyPose();
    this.showReticle();
    for (const h of this.hands) {
      if (!h.held) continue;
      h.grip.getWorldPosition(this.pos);
      h.grip.getWorldQuaternion(this.rot);
      // rotation since the grab, in three.js space
      const delta = this.rot.clone().multiply(h.grabRotation.clone().invert());
      this.net.send({
        type: 'move',
        hand_id: this.handBase + h.handId,
        position: this.stage.toWorld(this.pos),
        orientation: this.stage.toWorldRotation(delta),
      });
    }
  }

  /** In a session with a worker: the headset's eyes and gaze and the controllers'
   *  grips, at most BODY_POSE_HZ a second. */
  private sendBodyPose(): void {
    const now = performance.now();
    if (this.session === null || !this.worker || !bodyPoseDue(now, this.lastBodyPose)) return;
    const camera = this.stage.renderer.xr.getCamera();
    camera.getWorldPosition(this.pos);
    camera.getWorldDirection(this.ahead).add(this.pos);
    const grips = this.hands.map((h) => ({
      handedness: h.handedness,
      position: h.gamepad === null ? null : this.stage.toWorld(h.grip.getWorldPosition(new THREE.Vector3())),
    }));
    const message = bodyPoseMessage(this.stage.toWorld(this.pos), this.stage.toWorld(this.ahead), grips);
    if (message !== null && this.net.send(message)) this.lastBodyPose = now;
  }

  /** Forget held hands (the server released them: reset, new scene). */
  drop(): void {
    for (const h of this.hands) h.held = false;
  }
}
