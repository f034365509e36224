// Mouse hand (SPEC I1): pointer-down on a hose grabs the beam nearest to the ray; dragging
// moves the hand in the plane through the grab point facing the camera. Shift-drag or the
// wheel moves it along the view axis (depth); Alt- or Ctrl-drag turns the hand (about the
// view's up axis for horizontal motion, about its right axis for vertical motion).
// Pointer-up releases. Moves are sent at most once per frame. The grip (grips.ts) is the
// panel's choice, or the one of a key held at the grab: F firm, A axial, B ball.

import * as THREE from 'three';
import { gripFor, gripOfKey, type Grip } from './grips';
import { pickBeam, type HoseTube, type Pick } from './hoses';
import type { Net } from './net';
import type { Quat, Vec3 } from './protocol';
import type { Stage } from './scene';

/** Radians of hand turn per pixel of Alt/Ctrl-drag. */
const TURN_PER_PIXEL = 0.01;

export class MouseHand {
  /** hand_id of the mouse hand (unique per client: several viewers may share a session). */
  handId = 0;
  private active = false;
  private target = new THREE.Vector3(); // three.js space
  private orientation = new THREE.Quaternion(); // three.js space
  private plane = new THREE.Plane();
  private last = { x: 0, y: 0 };
  private dirty = false;
  private readonly raycaster = new THREE.Raycaster();
  lastPick: Pick | null = null;
  /** The panel's grip for the next grab. */
  grip: Grip = 'firm';
  /** The grip of the hand now held (or of the last grab). */
  heldGrip: Grip = 'firm';
  /** Grip keys held down now (`KeyboardEvent.code`). */
  private readonly gripKeys = new Set<string>();

  constructor(
    private readonly stage: Stage,
    private readonly tubes: () => HoseTube[],
    private readonly net: Net,
    private readonly enabled: () => boolean,
  ) {
    const el = stage.renderer.domElement;
    // capture phase on the container: runs before the orbit controls' own listeners
    stage.container.addEventListener('pointerdown', (e) => this.down(e), { capture: true });
    window.addEventListener('pointermove', (e) => this.move(e));
    window.addEventListener('pointerup', () => this.up());
    el.addEventListener('wheel', (e) => this.wheel(e), { passive: false, capture: true });
    window.addEventListener('keydown', (e) => {
      if (gripOfKey(e.code) !== null && !(e.target instanceof HTMLInputElement)) this.gripKeys.add(e.code);
    });
    window.addEventListener('keyup', (e) => this.gripKeys.delete(e.code));
    window.addEventListener('blur', () => this.gripKeys.clear());
  }

  get holding(): boolean {
    return this.active;
  }

  private ray(e: { clientX: number; clientY: number }): THREE.Ray {
    const r = this.stage.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.stage.camera);
    return this.raycaster.ray;
  }

  /** The beam under the pointer, if any. */
  pickAt(e: { clientX: number; clientY: number }): Pick | null {
    const ray = this.ray(e);
    const o = this.stage.toWorld(ray.origin.clone());
    const tip = this.stage.toWorld(ray.origin.clone().add(ray.direction));
    const d: Vec3 = [tip[0] - o[0], tip[1] - o[1], tip[2] - o[2]];
    const l = Math.hypot(d[0], d[1], d[2]);
    return pickBeam(this.tubes(), o, [d[0] / l, d[1] / l, d[2] / l]);
  }

  private down(e: PointerEvent): void {
    if (e.button !== 0 || !this.enabled() || e.target !== this.stage.renderer.domElement) return;
    const pick = this.pickAt(e);
    this.lastPick = pick;
    if (pick === null) return; // orbit instead
    e.stopPropagation();
    e.preventDefault();
    this.active = true;
    this.stage.controls.enabled = false;
    this.target.copy(this.stage.toThree(pick.point));
    this.orientation.identity();
    this.last = { x: e.clientX, y: e.clientY };
    const normal = this.stage.camera.getWorldDirection(new THREE.Vector3());
    this.plane.setFromNormalAndCoplanarPoint(normal, this.target);
    this.heldGrip = gripFor(this.grip, this.gripKeys);
    this.net.send({ type: 'grab', hand_id: this.handId, position: pick.point, grip: this.heldGrip });
  }

  private move(e: PointerEvent): void {
    if (!this.active) return;
    const dx = e.clientX - this.last.x;
    const dy = e.clientY - this.last.y;
    this.last = { x: e.clientX, y: e.clientY };
    const cam = this.stage.camera;
    if (e.altKey || e.ctrlKey) {
      const up = new THREE.Vector3(0, 1, 0).applyQuaternion(cam.quaternion);
      const right = new THREE.Vector3(1, 0, 0).applyQuaternion(cam.quaternion);
      const q = new THREE.Quaternion()
        .setFromAxisAngle(up, dx * TURN_PER_PIXEL)
        .multiply(new THREE.Quaternion().setFromAxisAngle(right, dy * TURN_PER_PIXEL));
      this.orientation.premultiply(q);
    } else if (e.shiftKey) {
      this.depth(-dy * this.pixelSize());
    } else {
      const hit = this.ray(e).intersectPlane(this.plane, new THREE.Vector3());
      if (hit !== null) this.target.copy(hit);
    }
    this.dirty = true;
  }

  /** Metres per pixel at the grab point's depth. */
  private pixelSize(): number {
    const cam = this.stage.camera;
    const dist = cam.position.distanceTo(this.target);
    const h = this.stage.renderer.domElement.clientHeight || 1;
    return (2 * dist * Math.tan((cam.fov * Math.PI) / 360)) / h;
  }

  /** Moves the hand along the view axis by `metres` (positive: away from the eye). */
  private depth(metres: number): void {
    const dir = this.stage.camera.getWorldDirection(new THREE.Vector3());
    this.target.addScaledVector(dir, metres);
    this.plane.setFromNormalAndCoplanarPoint(dir, this.target);
  }

  private wheel(e: WheelEvent): void {
    if (!this.active) return;
    e.preventDefault();
    e.stopPropagation();
    this.depth(Math.sign(e.deltaY) * 20 * this.pixelSize());
    this.dirty = true;
  }

  private up(): void {
    if (!this.active) return;
    this.flush();
    this.active = false;
    this.stage.controls.enabled = true;
    this.net.send({ type: 'release', hand_id: this.handId });
  }

  /** Sends the pending move, if any (called once per frame). */
  flush(): void {
    if (!this.active || !this.dirty) return;
    this.dirty = false;
    const position = this.stage.toWorld(this.target.clone());
    const orientation: Quat = this.stage.toWorldRotation(this.orientation);
    this.net.send({ type: 'move', hand_id: this.handId, position, orientation });
  }

  /** Forget a hand the server released (reset, new scene). */
  drop(): void {
    this.active = false;
    this.stage.controls.enabled = true;
  }
}
