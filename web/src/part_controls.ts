// The panel's moving parts and their handles in the 3-D view: per part that moves, a row
// with its joint coordinate — a slider for a hinge (its angle, sending `rotate_part` to
// it) or a slide (its travel, `move_part`) — and a handle (three.js TransformControls) on
// the part: about the hinge axis, along the slide, or free (move, or turn about the part's
// centre). A scripted motion's row follows the motion (inputs cannot move such a part).
// Which parts move and how is what the welcome tells (part_joints.ts).

import * as THREE from 'three';
import type { TransformControls } from 'three/examples/jsm/controls/TransformControls.js';
import type { Net } from './net';
import { el } from './panel';
import {
  carry, coordinateOfPose, coordinateToSlider, draggedCoordinate, dragInParent, jointMessage, ownPose, partControls, SLIDER_STEPS,
  sliderToCoordinate, turned, SLIDE_SPEED_M_S, HINGE_SPEED_DEG_S, MIN_MOVE_S, type Joint, type PartControl,
} from './part_joints';
import type { ClientMessage, PartData, PartPose, Vec3 } from './protocol';
import type { Stage } from './scene';

/** Least time between two moves sent while a slider or handle is dragged [ms]. */
const SEND_INTERVAL_MS = 100;

interface Row {
  control: PartControl;
  root: HTMLElement;
  readout: HTMLElement;
  slider: HTMLInputElement | null;
  /** The user holds the slider, or the part is on its way to where it was let go
   *  (until `settles`, performance.now ms): snapshots do not move it meanwhile. */
  held: boolean;
  settles: number;
}

const coordinateText = (joint: Joint, x: number) =>
  joint.kind === 'hinge' ? `${x.toFixed(1)}°` : `${(x * 1e3).toFixed(0)} mm`;

export class PartControls {
  private rows: Row[] = [];
  /** Each part's bounding-box centre where the scene placed it (world frame). */
  private centres: Vec3[] = [];
  /** Each part's parent (index) as the welcome gives it, or null. */
  private parents: (number | null)[] = [];
  private poses = new Map<number, PartPose>();
  private readonly gizmo: TransformControls;
  /** What the handle drags: a stand-in at the part's pivot, in the world frame. */
  private readonly proxy = new THREE.Object3D();
  private selected: Row | null = null;
  /** Free parts: the handle moves (translate) or turns (rotate) them. */
  private freeMode: 'translate' | 'rotate' = 'translate';
  private drag: { position: THREE.Vector3; quaternion: THREE.Quaternion; coordinate: number } | null = null;
  private lastSent = 0;
  private enabled = true;

  constructor(stage: Stage, private readonly net: Net, private readonly slot: HTMLElement) {
    this.proxy.name = 'part-handle';
    stage.world.add(this.proxy);
    this.gizmo = stage.handle(0.8, (on) => (on ? this.startDrag() : this.endDrag()));
    this.gizmo.addEventListener('objectChange', () => this.dragged(false));
    this.showRows();
  }

  /** A new session: its parts (their reference bounding boxes) and which of them move
   *  and how (a row each). */
  welcome(parts: readonly PartData[]): void {
    this.centres = parts.map((p) => [0, 1, 2].map((k) => (p.bounds_min[k] + p.bounds_max[k]) / 2) as Vec3);
    this.parents = parts.map((p) => p.parent ?? null);
    this.poses.clear();
    this.select(null);
    this.rows = partControls(parts).map((c) => this.row(c));
    this.showRows();
    this.refresh();
  }

  /** Replays and the author mode draw other things: the controls rest meanwhile. */
  setEnabled(on: boolean): void {
    this.enabled = on;
    if (!on) this.select(null);
    for (const r of this.rows) {
      if (r.slider !== null) r.slider.disabled = !on || !r.control.movable;
      for (const b of r.root.querySelectorAll('button')) b.disabled = !on || !r.control.movable;
    }
  }

  /** The pointer is over a handle: a press there drags it (not a hose, not the view). */
  get onHandle(): boolean {
    return this.gizmo.object !== undefined && this.gizmo.axis !== null;
  }

  /** The pose of part `k`'s parent in the snapshot drawn (null: it has none, or it stands
   *  where the scene placed it). */
  private parentPose(k: number): PartPose | null {
    const p = this.parents[k];
    return p === null || p === undefined ? null : this.poses.get(p) ?? null;
  }

  /** Part `k`'s own pose, in its parent's frame, where its joint is given (null: where
   *  the scene placed it). */
  private own(k: number): PartPose | null {
    const pose = this.poses.get(k);
    return pose === undefined ? null : ownPose(pose, this.parentPose(k));
  }

  /** The parts' poses of the snapshot drawn. */
  update(poses: readonly PartPose[]): void {
    for (const p of poses) this.poses.set(p.part, p);
    this.refresh();
  }

  /** The joint coordinate of each row as shown (degrees or metres; null without a joint). */
  shown(): { part: string; coordinate: number | null; slider: number | null }[] {
    return this.rows.map((r) => ({
      part: r.control.name,
      coordinate: r.control.joint === null ? null : coordinateOfPose(r.control.joint, this.own(r.control.part)),
      slider: r.slider === null ? null : Number(r.slider.value),
    }));
  }

  /** The last move sent by a slider or the handle. */
  lastMove: Extract<ClientMessage, { type: 'move_part' | 'rotate_part' }> | null = null;

  /** Points (three.js space) on the shown parts of the handle whose name is `axis`
   *  ("Z" a hinge's ring, "X" a slide's arrow): where a pointer grabs it. */
  handlePoints(axis: string): THREE.Vector3[] {
    if (this.gizmo.object === undefined) return [];
    const helper = this.gizmo.getHelper();
    helper.updateMatrixWorld(true);
    const out: THREE.Vector3[] = [];
    helper.traverse((o) => {
      const m = o as THREE.Mesh;
      if (o.name !== axis || !m.isMesh) return;
      let shown = true;
      o.traverseAncestors((a) => (shown &&= a.visible));
      if (!shown || !o.visible) return;
      const p = m.geometry.getAttribute('position');
      for (let i = 0; i < p.count; i += 7) out.push(new THREE.Vector3().fromBufferAttribute(p, i).applyMatrix4(o.matrixWorld));
    });
    return out;
  }

  private row(control: PartControl): Row {
    const root = el('div', { class: 'part-control', 'data-part': control.name });
    const readout = el('div', { class: 'part-readout' });
    const j = control.joint;
    let slider: HTMLInputElement | null = null;
    const r: Row = { control, root, readout, slider: null, held: false, settles: 0 };
    root.append(readout);
    if (j !== null) {
      slider = el('input', { type: 'range', min: '0', max: String(SLIDER_STEPS), value: String(coordinateToSlider(j, 0)), class: 'part-slider', 'data-part': control.name });
      slider.title = control.scripted ? 'follows the scripted motion' : j.kind === 'hinge' ? 'the hinge angle' : 'the travel along the slide';
      slider.disabled = !control.movable;
      const s = slider;
      s.addEventListener('pointerdown', () => (r.held = true));
      s.addEventListener('keydown', () => (r.held = true));
      s.addEventListener('input', () => this.sliderMoved(r, false));
      s.addEventListener('change', () => {
        this.sliderMoved(r, true);
        r.held = false;
      });
      root.append(s);
      r.slider = s;
    }
    if (control.movable) {
      const buttons = el('div', { class: 'row' });
      const handle = el('button', { class: 'part-handle-button', title: 'a handle on the part in the view: drag it' }, 'Handle');
      handle.onclick = () => this.select(this.selected === r ? null : r);
      buttons.append(handle);
      if (j === null) {
        const mode = el('button', { class: 'part-mode-button', title: 'the handle moves or turns the part' }, 'Turn');
        mode.onclick = () => {
          this.freeMode = this.freeMode === 'translate' ? 'rotate' : 'translate';
          mode.textContent = this.freeMode === 'translate' ? 'Turn' : 'Move';
          if (this.selected !== null) this.place(this.selected, true);
        };
        buttons.append(mode);
      }
      root.append(buttons);
    }
    return r;
  }

  private showRows(): void {
    this.slot.replaceChildren(...(this.rows.length === 0 ? [el('div', { class: 'muted' }, 'no part moves in this scene')] : this.rows.map((r) => r.root)));
    this.setEnabled(this.enabled);
  }

  private refresh(): void {
    for (const r of this.rows) {
      const c = r.control;
      const j = c.joint;
      const how = c.scripted ? 'scripted motion' : 'moved by you or the timeline';
      if (j === null) {
        r.readout.textContent = `${c.name}: ${c.scripted ? c.motion || 'scripted motion' : 'drag its handle'}`;
        continue;
      }
      const x = coordinateOfPose(j, this.own(c.part));
      r.readout.textContent = `${c.name}: ${j.kind} ${coordinateText(j, x)} (${coordinateText(j, j.min)} … ${coordinateText(j, j.max)}; ${how})`;
      if (r.slider !== null && !r.held && performance.now() >= r.settles) r.slider.value = String(coordinateToSlider(j, x));
    }
    if (this.selected !== null && this.drag === null) this.place(this.selected, false);
  }

  private sliderMoved(r: Row, final: boolean): void {
    const j = r.control.joint;
    if (j === null || r.slider === null || !this.enabled || !r.control.movable) return;
    const now = performance.now();
    if (!final && now - this.lastSent < SEND_INTERVAL_MS) return;
    this.lastSent = now;
    const from = coordinateOfPose(j, this.own(r.control.part));
    const message = jointMessage(r.control.name, j, sliderToCoordinate(j, Number(r.slider.value)), from);
    this.send(message);
    r.settles = now + message.duration_s * 1000;
  }

  private send(m: Extract<ClientMessage, { type: 'move_part' | 'rotate_part' }>): void {
    this.net.send(m);
    this.lastMove = m;
  }

  private select(r: Row | null): void {
    this.selected = r;
    for (const x of this.rows) x.root.classList.toggle('selected', x === r);
    if (r === null || !this.enabled) {
      this.gizmo.detach();
      return;
    }
    this.place(r, true);
    this.gizmo.attach(this.proxy);
  }

  /** Where the handle of `r` sits (world frame): the hinge point or the part's centre,
   *  carried by the part's pose. */
  private pivot(r: Row): Vec3 {
    const c = r.control;
    const pose = this.poses.get(c.part);
    const j = c.joint;
    const p = j !== null && j.kind === 'hinge' ? j.point : this.centres[c.part] ?? [0, 0, 0];
    return pose === undefined ? p : carry(pose, p);
  }

  /** Puts the stand-in at the part's pivot; with `modes`, sets the handle's kind: a ring
   *  about the hinge axis, an arrow along the slide, or free. */
  private place(r: Row, modes: boolean): void {
    const j = r.control.joint;
    this.proxy.position.set(...this.pivot(r));
    const pose = this.poses.get(r.control.part);
    if (j === null) {
      if (pose !== undefined) this.proxy.quaternion.set(...pose.rotation);
      else this.proxy.quaternion.identity();
    } else {
      const parent = this.parentPose(r.control.part);
      const own = j.kind === 'hinge' ? j.axis : j.direction;
      const along = parent === null ? own : turned(parent.rotation, own);
      const local = j.kind === 'hinge' ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, 0, 0);
      this.proxy.quaternion.setFromUnitVectors(local, new THREE.Vector3(...along));
    }
    if (!modes) return;
    if (j === null) {
      this.gizmo.setMode(this.freeMode);
      this.gizmo.setSpace('world');
      this.gizmo.showX = this.gizmo.showY = this.gizmo.showZ = true;
    } else {
      this.gizmo.setMode(j.kind === 'hinge' ? 'rotate' : 'translate');
      this.gizmo.setSpace('local');
      this.gizmo.showX = j.kind === 'slide';
      this.gizmo.showY = false;
      this.gizmo.showZ = j.kind === 'hinge';
    }
  }

  private startDrag(): void {
    const r = this.selected;
    if (r === null) return;
    const j = r.control.joint;
    this.drag = {
      position: this.proxy.position.clone(),
      quaternion: this.proxy.quaternion.clone(),
      coordinate: j === null ? 0 : coordinateOfPose(j, this.own(r.control.part)),
    };
  }

  private endDrag(): void {
    this.dragged(true);
    this.drag = null;
  }

  /** The handle moved: sends the part after it (at most every SEND_INTERVAL_MS while
   *  dragging; a free turn only when let go, as one turn `by` its angle). */
  private dragged(final: boolean): void {
    const r = this.selected;
    const d = this.drag;
    if (r === null || d === null || !this.enabled) return;
    const now = performance.now();
    if (!final && now - this.lastSent < SEND_INTERVAL_MS) return;
    const c = r.control;
    const j = c.joint;
    // the turn and the shift of the stand-in since the drag began (world frame)
    const turn = this.proxy.quaternion.clone().multiply(d.quaternion.clone().invert());
    const shift = this.proxy.position.clone().sub(d.position);
    if (j !== null) {
      // a child's joint is given in its parent's frame
      const seen = dragInParent(this.parentPose(c.part), [turn.x, turn.y, turn.z, turn.w], [shift.x, shift.y, shift.z]);
      const x = draggedCoordinate(j, d.coordinate, seen.turn, seen.shift);
      this.lastSent = now;
      this.send(jointMessage(c.name, j, x, coordinateOfPose(j, this.own(c.part))));
      return;
    }
    if (this.freeMode === 'translate') {
      const centre = this.centres[c.part] ?? [0, 0, 0];
      const to: Vec3 = [this.proxy.position.x - centre[0], this.proxy.position.y - centre[1], this.proxy.position.z - centre[2]];
      const here = this.pivot(r);
      const way = Math.hypot(this.proxy.position.x - here[0], this.proxy.position.y - here[1], this.proxy.position.z - here[2]);
      this.lastSent = now;
      this.send({ type: 'move_part', part: c.name, to, duration_s: Math.max(MIN_MOVE_S, way / SLIDE_SPEED_M_S) });
      return;
    }
    if (!final) return;
    const angle = 2 * Math.acos(Math.min(1, Math.abs(turn.w)));
    if (angle < 1e-6) return;
    const s = Math.sign(turn.w) || 1;
    const axis: Vec3 = [turn.x * s, turn.y * s, turn.z * s];
    const deg = (angle * 180) / Math.PI;
    this.lastSent = now;
    this.send({ type: 'rotate_part', part: c.name, axis, by_deg: deg, duration_s: Math.max(MIN_MOVE_S, deg / HINGE_SPEED_DEG_S) });
  }
}
