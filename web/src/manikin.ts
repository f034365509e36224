// The worker drawn (docs/worker.md): one capsule per body segment — a cylinder on the
// axis and a ball at each end, shared unit geometry scaled per frame — placed from each
// snapshot's `worker` (live and in replays); a segment inside a part or hose is red, and
// the panel lists reach, contacts and the posture scores (manikin_model.ts). When the
// worker steps or turns, the body glides to the new stance over STEP_DRAW_S (`tick`, each
// frame) instead of jumping there. A seated worker's seat is drawn as a grey box.

import * as THREE from 'three';
import { el } from './panel';
import { glide, manikinCapsules, manikinLines, seatBox, STEP_DRAW_S, stepped, type ManikinCapsule } from './manikin_model';
import type { Snapshot, WorkerData } from './protocol';

const BODY_COLOUR = 0xc8b08c;
const CONTACT_COLOUR = 0xe5484d;
const SEAT_COLOUR = 0x7a7f87;
const Y = new THREE.Vector3(0, 1, 0);

interface DrawnSegment {
  shaft: THREE.Mesh;
  ends: [THREE.Mesh, THREE.Mesh];
  material: THREE.MeshStandardMaterial;
}

export class ManikinView {
  readonly group = new THREE.Group();
  private readonly cylinder = new THREE.CylinderGeometry(1, 1, 1, 16, 1);
  private readonly sphere = new THREE.SphereGeometry(1, 16, 12);
  private segments: DrawnSegment[] = [];
  private data: WorkerData | null = null;
  private readonly dir = new THREE.Vector3();
  /** The capsules of the last snapshot (for tests and the panel). */
  drawn: ManikinCapsule[] = [];
  /** The capsules on screen now (`drawn`, or on the way there during a step). */
  private shown: ManikinCapsule[] = [];
  private lastPose: Snapshot['worker'] = undefined;
  /** A step being drawn: the capsules it started from and when [performance.now ms]. */
  private gliding: { from: ManikinCapsule[]; start: number } | null = null;
  private linesShown = '';
  /** A seated worker's seat (hidden while standing). */
  private readonly seat = new THREE.Mesh(
    new THREE.BoxGeometry(1, 1, 1),
    new THREE.MeshStandardMaterial({ color: SEAT_COLOUR, roughness: 0.8 }),
  );
  private readonly basis = new THREE.Matrix4();

  constructor(private readonly slot: HTMLElement) {
    this.group.name = 'manikin';
    this.group.visible = false;
    this.seat.name = 'manikin:seat';
    this.seat.visible = false;
  }

  /** A new session: its worker's segments (none: nothing is drawn). */
  welcome(data: WorkerData | undefined): void {
    this.clear();
    this.data = data ?? null;
    this.linesShown = '';
    if (this.data === null) {
      this.slot.replaceChildren(el('div', { class: 'muted' }, 'no worker in this scene'));
      return;
    }
    this.group.add(this.seat);
    this.segments = this.data.segments.map((name) => {
      const material = new THREE.MeshStandardMaterial({ color: BODY_COLOUR, roughness: 0.7, transparent: true, opacity: 0.85 });
      const shaft = new THREE.Mesh(this.cylinder, material);
      const ends: [THREE.Mesh, THREE.Mesh] = [new THREE.Mesh(this.sphere, material), new THREE.Mesh(this.sphere, material)];
      shaft.name = `manikin:${name}`;
      for (const m of [shaft, ...ends]) m.castShadow = true;
      this.group.add(shaft, ...ends);
      return { shaft, ends, material };
    });
    this.update(undefined, { parts: [], hoses: [] });
  }

  /** Places the capsules from the snapshot's worker (hidden until it is posed) and
   *  writes the panel's lines; a step or turn starts a glide from what is on screen. */
  update(pose: Snapshot['worker'], names: { parts: readonly string[]; hoses: readonly string[] }): void {
    const data = this.data;
    if (data === null) return;
    this.drawn = pose === undefined ? [] : manikinCapsules(data, pose, names);
    this.group.visible = this.drawn.length > 0;
    if (stepped(this.lastPose, pose) && this.shown.length === this.drawn.length) {
      this.gliding = { from: this.shown, start: performance.now() };
    }
    this.lastPose = pose;
    this.placeSeat(pose);
    if (this.gliding === null) this.place(this.drawn);
    else this.tick(performance.now());
    const lines = manikinLines(data, pose, this.drawn);
    const key = lines.join('\n');
    if (key === this.linesShown) return;
    this.linesShown = key;
    this.slot.replaceChildren(...lines.map((l, i) => el('div', { class: i === 0 ? 'worker-scores' : 'worker-line' }, l)));
  }

  /** Each frame: moves a step being drawn on to time `now` [performance.now ms]. */
  tick(now: number): void {
    if (this.gliding === null) return;
    const f = (now - this.gliding.start) / (1000 * STEP_DRAW_S);
    if (f >= 1) this.gliding = null;
    this.place(f >= 1 ? this.drawn : glide(this.gliding?.from ?? this.drawn, this.drawn, f));
  }

  /** The seat as drawn: shown or not, its mesh's centre and scale (its full lengths). */
  seatDrawn(): { visible: boolean; centre: number[]; size: number[] } {
    const s = this.seat;
    return { visible: s.visible && this.group.visible, centre: s.position.toArray(), size: s.scale.toArray() };
  }

  /** Puts the seat box where the snapshot says (hidden without one). */
  private placeSeat(pose: Snapshot['worker']): void {
    const box = seatBox(pose);
    this.seat.visible = box !== null;
    if (box === null) return;
    const v = (a: readonly number[]) => new THREE.Vector3(a[0], a[1], a[2]);
    this.basis.makeBasis(v(box.forward), v(box.left), v(box.up));
    this.seat.quaternion.setFromRotationMatrix(this.basis);
    this.seat.scale.set(box.size[0], box.size[1], box.size[2]);
    this.seat.position.set(box.centre[0], box.centre[1], box.centre[2]);
  }

  /** Puts the segments' meshes on the capsules `caps`. */
  private place(caps: ManikinCapsule[]): void {
    this.shown = caps;
    caps.forEach((c, i) => {
      const d = this.segments[i];
      if (d === undefined) return;
      const r = Math.max(c.radius, 1e-4);
      this.dir.set(c.b[0] - c.a[0], c.b[1] - c.a[1], c.b[2] - c.a[2]);
      const length = this.dir.length();
      d.shaft.visible = length > 1e-9;
      if (d.shaft.visible) {
        d.shaft.quaternion.setFromUnitVectors(Y, this.dir.multiplyScalar(1 / length));
        d.shaft.scale.set(r, length, r);
        d.shaft.position.set(0.5 * (c.a[0] + c.b[0]), 0.5 * (c.a[1] + c.b[1]), 0.5 * (c.a[2] + c.b[2]));
      }
      d.ends[0].position.set(...c.a);
      d.ends[1].position.set(...c.b);
      for (const e of d.ends) e.scale.setScalar(r);
      d.material.color.setHex(c.contact === null ? BODY_COLOUR : CONTACT_COLOUR);
      d.shaft.userData.contact = c.contact !== null;
    });
  }

  private clear(): void {
    for (const d of this.segments) d.material.dispose();
    this.group.clear();
    this.seat.visible = false;
    this.segments = [];
    this.drawn = [];
    this.shown = [];
    this.lastPose = undefined;
    this.gliding = null;
    this.group.visible = false;
  }
}
