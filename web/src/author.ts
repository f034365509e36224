// Scene authoring in the viewer (docs/authoring.md). The "Author" mode
// edits a scene document in the page: the served scene file's own structure (from
// `scene_source`: parts, settings and all) plus the hoses, stubs and clips made here by
// clicking on part surfaces. Hoses are splines through clicked points (each lifted off the
// surface by the hose's outer radius, so that it rests on it), optionally snapped to the
// parts' feature edges; a stub stands on the clicked surface with its axis along the
// normal; a clip sits where a hose would rest, opening along the normal and oriented along
// the nearest hose. Points move with handles (TransformControls); every change is a step of
// an undo/redo history (the document and its history: author_document.ts). "Save & run"
// writes the document as TOML (toml.ts), downloads it and sends it with `load_scene`: the
// server's loader checks it (its errors, naming the field, are shown here) and the session
// runs it.

import * as THREE from 'three';
import type { TransformControls } from 'three/examples/jsm/controls/TransformControls.js';
import type { Net } from './net';
import type { FastenerData, LibraryHose, SceneSourceMessage, Vec3 } from './protocol';
import { download } from './record';
import { clipMesh, disposeTree, stubMesh, type Stage } from './scene';
import { EditHistory, sceneDocument, type AuthorHose, type AuthorState, type ClipType, type Doc } from './author_document';
import { toToml } from './toml';

export type { AuthorClip, AuthorHose, AuthorState, AuthorStub, ClipType } from './author_document';

export type Tool = 'hose' | 'stub' | 'clip' | 'move';

/** What a handle moves. */
type HandleRef = { kind: 'hose'; i: number; k: number } | { kind: 'stub'; i: number } | { kind: 'clip'; i: number };

/** A surface hit in the world frame: the point, the unit normal facing the viewer. */
export interface SurfaceHit { point: Vec3; normal: Vec3; part: string; snapped: boolean }

const add = (a: Vec3, b: Vec3, s = 1): Vec3 => [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s];
const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const len = (a: Vec3) => Math.sqrt(dot(a, a));
const unit = (a: Vec3): Vec3 => { const l = len(a) || 1; return [a[0] / l, a[1] / l, a[2] / l]; };
const dist = (a: Vec3, b: Vec3) => len(sub(a, b));

/** Points closer than this [m] to the previous one are not added (the loader refuses
 *  equal consecutive spline points). */
const MIN_SPACING = 0.002;

/** Samples of the uniform Catmull-Rom spline through `pts` (as the loader builds it;
 *  three.js extrapolates the end tangents slightly differently: a preview). */
export function splineSamples(pts: Vec3[], perSpan = 12): Vec3[] {
  if (pts.length < 2) return pts.slice();
  const curve = new THREE.CatmullRomCurve3(pts.map((p) => new THREE.Vector3(...p)), false, 'catmullrom', 0.5);
  return curve.getPoints((pts.length - 1) * perSpan).map((v) => [v.x, v.y, v.z] as Vec3);
}

export interface AuthorCallbacks {
  /** Called when the author mode turns on or off (the mouse hand stays off meanwhile). */
  changed(active: boolean): void;
}

export class Author {
  active = false;
  tool: Tool = 'hose';
  state: AuthorState | null = null;
  /** The library from `scene_source`. */
  library: LibraryHose[] = [];
  unit = 'mm';
  private readonly history = new EditHistory();
  /** Index of the hose being drawn (more clicks add points to it), or null. */
  drawing: number | null = null;
  /** The hose the material and section controls act on. */
  selectedHose: number | null = null;
  selected: HandleRef | null = null;
  lastToml = '';
  lastSaveName = '';
  /** Waiting for the answer to a `load_scene` we sent. */
  private saving = false;
  readonly root: HTMLElement;
  private readonly group = new THREE.Group();
  private handles: { mesh: THREE.Mesh; ref: HandleRef }[] = [];
  private readonly gizmo: TransformControls;
  private gizmoDragging = false;
  private gizmoUsed = false;
  private dragBefore = '';
  private down: { x: number; y: number } | null = null;
  private readonly raycaster = new THREE.Raycaster();
  private edgeCache = new Map<string, Float32Array>();
  private readonly ui: Record<string, HTMLElement> = {};
  /** A `scene_source` was asked for by this mode and not answered yet. */
  private asked = false;

  constructor(private readonly stage: Stage, private readonly net: Net, panel: HTMLElement, private readonly cb: AuthorCallbacks) {
    this.group.name = 'author';
    stage.world.add(this.group);
    this.gizmo = stage.handle(0.7, (on) => {
      this.gizmoDragging = on;
      if (on) {
        this.gizmoUsed = true;
        this.dragBefore = this.snapshot();
      } else {
        this.commitDrag();
      }
    });
    this.root = this.buildPanel(panel);
    const canvas = stage.renderer.domElement;
    canvas.addEventListener('pointerdown', (e) => {
      if (!this.active || e.button !== 0) return;
      this.down = { x: e.clientX, y: e.clientY };
      this.gizmoUsed = this.gizmoDragging;
    });
    canvas.addEventListener('pointerup', (e) => {
      if (!this.active || e.button !== 0 || this.down === null) return;
      const moved = Math.hypot(e.clientX - this.down.x, e.clientY - this.down.y);
      this.down = null;
      if (moved > 5 || this.gizmoUsed || this.gizmoDragging) return; // an orbit or a handle drag
      this.click(e);
    });
    canvas.addEventListener('dblclick', () => {
      if (this.active && this.tool === 'hose') this.finishHose();
    });
    window.addEventListener('keydown', (e) => this.key(e));
  }

  // ---------------------------------------------------------------- panel

  private buildPanel(panel: HTMLElement): HTMLElement {
    const el = <K extends keyof HTMLElementTagNameMap>(tag: K, attrs: Record<string, string> = {}, text?: string) => {
      const e = document.createElement(tag);
      for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
      if (text !== undefined) e.textContent = text;
      if (attrs.id) this.ui[attrs.id] = e;
      return e;
    };
    const root = el('section', { id: 'author' });
    root.hidden = true;
    const tools = el('div', { class: 'row', id: 'author-tools' });
    const toolNames: [Tool, string, string][] = [
      ['hose', 'Hose', 'click points on part surfaces; Enter or double-click finishes the hose'],
      ['stub', 'Stub', 'click a surface: a stub standing on it, axis along the normal'],
      ['clip', 'Clip', 'click a surface: a clip where a hose would rest, along the nearest hose'],
      ['move', 'Move', 'click a point, stub or clip, then drag its handle'],
    ];
    for (const [t, label, title] of toolNames) {
      const b = el('button', { id: `tool-${t}`, title }, label);
      b.onclick = () => this.setTool(t);
      tools.append(b);
    }
    const hoseRow = el('div', { class: 'row' });
    const material = el('select', { id: 'author-material', title: 'material of the selected hose (library or the scene\'s [materials])' });
    const dIn = el('input', { id: 'author-d-inner', type: 'number', step: '0.1', min: '0', title: 'inner diameter, mm' });
    const dOut = el('input', { id: 'author-d-outer', type: 'number', step: '0.1', min: '0', title: 'outer diameter, mm' });
    material.onchange = () => this.materialChanged();
    dIn.onchange = dOut.onchange = () => this.sectionChanged();
    hoseRow.append(material, el('span', { class: 'muted' }, 'd'), dIn, el('span', { class: 'muted' }, '/'), dOut, el('span', { class: 'muted' }, 'mm'));
    const optRow = el('div', { class: 'row' });
    const fix = el('input', { id: 'author-fix', type: 'checkbox', checked: '' });
    const snap = el('input', { id: 'author-snap', type: 'checkbox' });
    const clipType = el('select', { id: 'author-clip-type', title: 'type of new clips' });
    for (const t of ['fixed', 'rotating', 'sliding', 'cable_tie']) clipType.append(el('option', { value: t }, t));
    fix.onchange = () => this.fixChanged();
    const l1 = el('label', { title: 'the first point is fixed (a leading fix: the live session starts with it)' });
    l1.append(fix, ' fix start');
    const l2 = el('label', { title: 'snap clicks to the parts\' feature edges and corners (CAD edges)' });
    l2.append(snap, ' snap to edges');
    optRow.append(l1, l2, el('span', { class: 'muted' }, 'clip'), clipType);
    const editRow = el('div', { class: 'row' });
    const finish = el('button', { id: 'author-finish', title: 'Enter / double-click' }, 'Finish hose');
    const undo = el('button', { id: 'author-undo', title: 'Ctrl+Z' }, 'Undo');
    const redo = el('button', { id: 'author-redo', title: 'Ctrl+Shift+Z' }, 'Redo');
    const del = el('button', { id: 'author-delete', title: 'Delete: remove the selected point, stub or clip' }, 'Delete');
    const clear = el('button', { id: 'author-clear', title: 'remove every hose, stub, clip and timeline action; keep the parts' }, 'Clear');
    finish.onclick = () => this.finishHose();
    undo.onclick = () => this.undo();
    redo.onclick = () => this.redo();
    del.onclick = () => this.deleteSelected();
    clear.onclick = () => this.clear();
    editRow.append(finish, undo, redo, del, clear);
    const saveRow = el('div', { class: 'row' });
    const name = el('input', { id: 'author-name', type: 'text', value: 'authored', title: 'scene name (and file name)' });
    const save = el('button', { id: 'author-save', title: 'download the scene file and run it in this session' }, 'Save & run');
    save.onclick = () => this.save();
    saveRow.append(name, save);
    const summary = el('div', { id: 'author-summary', class: 'muted' });
    const message = el('div', { id: 'author-message' });
    root.append(el('h2', {}, 'Author'), tools, hoseRow, optRow, editRow, saveRow, summary, message);
    // a clicked button gives up the focus: Enter then finishes the hose instead of
    // pressing the button again
    root.addEventListener('click', (e) => {
      const t = e.target as HTMLElement;
      if (t.tagName === 'BUTTON') t.blur();
    });
    panel.append(root);
    return root;
  }

  private input(id: string): HTMLInputElement {
    return this.ui[id] as HTMLInputElement;
  }

  private say(text: string, error = false): void {
    const m = this.ui['author-message'];
    m.textContent = text;
    m.className = error ? 'error' : '';
  }

  /** Turns the mode on (asks the server for the scene document) or off. */
  toggle(on = !this.active): void {
    this.active = on;
    this.root.hidden = !on;
    this.group.visible = on;
    for (const x of ['hose', 'stub', 'clip', 'move']) this.ui[`tool-${x}`].classList.toggle('on', x === this.tool);
    if (on) {
      this.asked = true;
      this.net.send({ type: 'scene_source' });
      this.say('reading the scene…');
    } else {
      this.asked = false;
      this.gizmo.detach();
      this.drawing = null;
    }
    this.cb.changed(on);
  }

  /** The answer to `scene_source`: the document authoring starts from (authored hoses,
   *  stubs and clips so far are kept on top of it). */
  source(m: SceneSourceMessage): void {
    // only an answer to the author's own question starts (or restarts) authoring
    if (!this.asked) return;
    this.asked = false;
    this.library = m.library;
    this.unit = m.length_unit;
    if (m.document === null || typeof m.document !== 'object' || Array.isArray(m.document)) {
      this.say('the scene file could not be read as a document', true);
      return;
    }
    // a new document when nothing was edited yet (e.g. another scene was opened since);
    // edits so far are kept, on the document they started from
    const untouched = this.state === null || this.history.untouched;
    if (untouched) {
      this.state = { base: m.document as Doc, hoses: [], stubs: [], clips: [] };
      const name = this.input('author-name');
      name.value = `${m.scene} (authored)`.replace(/[^\w .()-]/g, '_');
    }
    this.fillMaterials();
    this.say(`authoring on ${m.scene}: click a part surface`);
    this.redraw();
  }

  private fillMaterials(): void {
    const sel = this.ui['author-material'] as HTMLSelectElement;
    const keep = sel.value;
    sel.innerHTML = '';
    for (const l of this.library) {
      const o = document.createElement('option');
      o.value = l.name;
      o.textContent = `${l.name}: ${l.description} (${(l.d_inner * 1000).toFixed(1)}/${(l.d_outer * 1000).toFixed(1)} mm)`;
      sel.append(o);
    }
    const user = this.state?.base.materials;
    if (user !== null && typeof user === 'object' && !Array.isArray(user)) {
      for (const n of Object.keys(user)) {
        const o = document.createElement('option');
        o.value = n;
        o.textContent = `${n} (scene material)`;
        sel.append(o);
      }
    }
    sel.value = keep !== '' && [...sel.options].some((o) => o.value === keep) ? keep : this.library.find((l) => l.name === 'hose3') ? 'hose3' : sel.options[0]?.value ?? '';
    this.showSection(this.currentSection());
  }

  setTool(t: Tool): void {
    if (t !== 'hose') this.finishHose();
    this.tool = t;
    for (const x of ['hose', 'stub', 'clip', 'move']) this.ui[`tool-${x}`].classList.toggle('on', x === t);
    if (t !== 'move') {
      this.gizmo.detach();
      this.selected = null;
    }
    this.redraw();
  }

  // ---------------------------------------------------------------- sections

  /** The section chosen in the panel, metres. */
  private currentSection(): { d_inner: number; d_outer: number } {
    const m = (this.ui['author-material'] as HTMLSelectElement).value;
    const lib = this.library.find((l) => l.name === m);
    const din = Number(this.input('author-d-inner').value) / 1000;
    const dout = Number(this.input('author-d-outer').value) / 1000;
    if (Number.isFinite(din) && Number.isFinite(dout) && dout > 0) return { d_inner: din, d_outer: dout };
    return lib ? { d_inner: lib.d_inner, d_outer: lib.d_outer } : { d_inner: 0.027, d_outer: 0.035 };
  }

  private showSection(s: { d_inner: number; d_outer: number }): void {
    this.input('author-d-inner').value = String(+(s.d_inner * 1000).toFixed(3));
    this.input('author-d-outer').value = String(+(s.d_outer * 1000).toFixed(3));
  }

  /** A hose's section, metres (its own, else its library hose's). */
  hoseSection(h: AuthorHose): { d_inner: number; d_outer: number } {
    if (h.section !== null) return h.section;
    const lib = this.library.find((l) => l.name === h.material);
    return lib ? { d_inner: lib.d_inner, d_outer: lib.d_outer } : { d_inner: 0.027, d_outer: 0.035 };
  }

  /** The panel's section as a hose would store it: null when it is the library's own. */
  private panelSection(material: string): { d_inner: number; d_outer: number } | null {
    const s = this.currentSection();
    const lib = this.library.find((l) => l.name === material);
    if (lib && Math.abs(lib.d_inner - s.d_inner) < 1e-9 && Math.abs(lib.d_outer - s.d_outer) < 1e-9) return null;
    return s;
  }

  private materialChanged(): void {
    const m = (this.ui['author-material'] as HTMLSelectElement).value;
    const lib = this.library.find((l) => l.name === m);
    if (lib) this.showSection({ d_inner: lib.d_inner, d_outer: lib.d_outer });
    this.applyToSelected();
  }

  private sectionChanged(): void {
    this.applyToSelected();
  }

  private fixChanged(): void {
    const h = this.selectedHoseObj();
    if (h === null) return;
    this.change(() => {
      h.fixStart = this.input('author-fix').checked;
    });
  }

  private selectedHoseObj(): AuthorHose | null {
    if (this.state === null || this.selectedHose === null) return null;
    return this.state.hoses[this.selectedHose] ?? null;
  }

  /** Material and section controls act on the selected hose. */
  private applyToSelected(): void {
    const h = this.selectedHoseObj();
    if (h === null) return;
    const material = (this.ui['author-material'] as HTMLSelectElement).value;
    this.change(() => {
      h.material = material;
      h.section = this.panelSection(material);
    });
  }

  // ---------------------------------------------------------------- history

  private snapshot(): string {
    return JSON.stringify({ s: this.state, d: this.drawing, h: this.selectedHose });
  }

  private restore(text: string): void {
    const v = JSON.parse(text) as { s: AuthorState; d: number | null; h: number | null };
    this.state = v.s;
    this.drawing = v.d;
    this.selectedHose = v.h;
    this.selected = null;
    this.gizmo.detach();
    this.redraw();
  }

  /** Applies an edit as one undoable step. */
  change(edit: () => void): void {
    if (this.state === null) return;
    const before = this.snapshot();
    edit();
    this.history.record(before);
    this.redraw();
  }

  undo(): void {
    const prev = this.history.undo(this.snapshot());
    if (prev !== null) this.restore(prev);
  }

  redo(): void {
    const next = this.history.redo(this.snapshot());
    if (next !== null) this.restore(next);
  }

  get canUndo(): boolean { return this.history.canUndo; }
  get canRedo(): boolean { return this.history.canRedo; }

  private key(e: KeyboardEvent): void {
    if (!this.active) return;
    const t = e.target as HTMLElement | null;
    // typing in a text field or choosing in a list is not a shortcut; a checkbox is no text
    const typing = t !== null && ((t.tagName === 'INPUT' && !['checkbox', 'radio', 'button'].includes((t as HTMLInputElement).type)) || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA');
    if (typing) return;
    const mod = e.ctrlKey || e.metaKey;
    if (mod && (e.key === 'z' || e.key === 'Z')) {
      e.preventDefault();
      if (e.shiftKey) this.redo();
      else this.undo();
    } else if (mod && (e.key === 'y' || e.key === 'Y')) {
      e.preventDefault();
      this.redo();
    } else if (e.key === 'Enter' || e.key === 'Escape') {
      this.finishHose();
    } else if (e.key === 'Delete' || e.key === 'Backspace') {
      this.deleteSelected();
    }
  }

  // ---------------------------------------------------------------- picking

  private rayAt(e: { clientX: number; clientY: number }): THREE.Raycaster {
    const r = this.stage.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.stage.camera);
    return this.raycaster;
  }

  /** The part surface under the pointer (world frame), snapped to a feature edge or corner
   *  when "snap to edges" is on and one is within 12 pixels. */
  surfaceAt(e: { clientX: number; clientY: number }): SurfaceHit | null {
    const rc = this.rayAt(e);
    const hits = rc.intersectObjects(this.stage.partMeshes(), false);
    const hit = hits[0];
    if (hit === undefined || hit.face == null) return null;
    const point = this.stage.toWorld(hit.point.clone());
    // the geometry is in the world frame (parts carry no transform of their own)
    let normal = unit([hit.face.normal.x, hit.face.normal.y, hit.face.normal.z]);
    const o = this.stage.toWorld(rc.ray.origin.clone());
    const d = sub(point, o);
    if (dot(normal, d) > 0) normal = [-normal[0], -normal[1], -normal[2]]; // facing the eye
    const mesh = hit.object as THREE.Mesh;
    let snapped = false;
    let p = point;
    if (this.input('author-snap').checked) {
      const tol = 12 * this.pixelSize(hit.distance);
      const s = this.nearestEdgePoint(mesh, point, tol);
      if (s !== null) {
        p = s;
        snapped = true;
      }
    }
    return { point: p, normal, part: mesh.name.replace(/^part:/, ''), snapped };
  }

  private pixelSize(distance: number): number {
    const h = this.stage.renderer.domElement.clientHeight || 1;
    return (2 * distance * Math.tan((this.stage.camera.fov * Math.PI) / 360)) / h;
  }

  /** Feature edges of a part (dihedral angle over 20°), as segments, world frame. */
  private edges(mesh: THREE.Mesh): Float32Array {
    let e = this.edgeCache.get(mesh.uuid);
    if (e === undefined) {
      const g = new THREE.EdgesGeometry(mesh.geometry, 20);
      e = (g.getAttribute('position').array as Float32Array).slice();
      g.dispose();
      this.edgeCache.set(mesh.uuid, e);
    }
    return e;
  }

  /** The nearest corner (within `tol`), else the nearest point on a feature edge. */
  private nearestEdgePoint(mesh: THREE.Mesh, p: Vec3, tol: number): Vec3 | null {
    const e = this.edges(mesh);
    let best: Vec3 | null = null;
    let bestD = tol;
    let corner: Vec3 | null = null;
    let cornerD = tol;
    for (let i = 0; i + 5 < e.length; i += 6) {
      const a: Vec3 = [e[i], e[i + 1], e[i + 2]];
      const b: Vec3 = [e[i + 3], e[i + 4], e[i + 5]];
      for (const c of [a, b]) {
        const dc = dist(c, p);
        if (dc < cornerD) { cornerD = dc; corner = c; }
      }
      const ab = sub(b, a);
      const l2 = dot(ab, ab);
      if (l2 === 0) continue;
      const t = Math.max(0, Math.min(1, dot(sub(p, a), ab) / l2));
      const q = add(a, ab, t);
      const dq = dist(q, p);
      if (dq < bestD) { bestD = dq; best = q; }
    }
    return corner ?? best;
  }

  private click(e: PointerEvent | MouseEvent): void {
    if (this.state === null) return;
    if (this.tool === 'move') {
      this.pickHandle(e);
      return;
    }
    const hit = this.surfaceAt(e);
    if (hit === null) {
      this.say('click on a part surface', true);
      return;
    }
    if (this.tool === 'hose') this.addPoint(hit);
    else if (this.tool === 'stub') this.addStub(hit);
    else this.addClip(hit);
  }

  private pickHandle(e: { clientX: number; clientY: number }): void {
    const rc = this.rayAt(e);
    const hits = rc.intersectObjects(this.handles.map((h) => h.mesh), false);
    const h = hits[0] ? this.handles.find((x) => x.mesh === hits[0].object) : undefined;
    if (h === undefined) {
      this.selected = null;
      this.gizmo.detach();
      return;
    }
    this.select(h.ref);
  }

  /** Selects a point, stub or clip: its handle gets the move gizmo. */
  select(ref: HandleRef | null): void {
    this.selected = ref;
    if (ref?.kind === 'hose') {
      this.selectedHose = ref.i;
      const h = this.state?.hoses[ref.i];
      if (h) this.showHose(h);
    }
    this.redraw();
  }

  private showHose(h: AuthorHose): void {
    (this.ui['author-material'] as HTMLSelectElement).value = h.material;
    this.showSection(this.hoseSection(h));
    this.input('author-fix').checked = h.fixStart;
  }

  // ---------------------------------------------------------------- edits

  private uniqueName(prefix: string, taken: string[]): string {
    for (let i = 1; ; i++) {
      const n = `${prefix}${i}`;
      if (!taken.includes(n)) return n;
    }
  }

  /** Names of the document's hoses (the base scene's and the authored ones). */
  hoseNames(): string[] {
    const base = Array.isArray(this.state?.base.hoses) ? (this.state?.base.hoses as { name?: string }[]) : [];
    return [...base.map((h) => String(h.name)), ...(this.state?.hoses ?? []).map((h) => h.name)];
  }

  private fastenerNames(): string[] {
    const s = this.state;
    if (s === null) return [];
    const base = (k: string) => (Array.isArray(s.base[k]) ? (s.base[k] as { name?: string }[]).map((x) => String(x.name)) : []);
    return [...base('stubs'), ...base('clips'), ...s.stubs.map((x) => x.name), ...s.clips.map((x) => x.name)];
  }

  /** Adds a point to the hose being drawn (a new hose on the first click). */
  addPoint(hit: SurfaceHit): void {
    const s = this.state;
    if (s === null) return;
    const material = (this.ui['author-material'] as HTMLSelectElement).value;
    const section = this.panelSection(material);
    const r = (section ?? this.currentSection()).d_outer / 2;
    const p = add(hit.point, hit.normal, r);
    const cur = this.drawing === null ? null : s.hoses[this.drawing];
    if (cur && dist(cur.points[cur.points.length - 1], p) < MIN_SPACING) return; // a double-click's second click
    this.change(() => {
      if (cur) {
        cur.points.push(p);
      } else {
        s.hoses.push({ name: this.uniqueName('hose', this.hoseNames()), material, section, points: [p], fixStart: this.input('author-fix').checked });
        this.drawing = s.hoses.length - 1;
        this.selectedHose = this.drawing;
      }
    });
    const h = s.hoses[this.drawing as number];
    this.say(`${h.name}: ${h.points.length} point(s)${hit.snapped ? ' (snapped to an edge)' : ''} — Enter or double-click finishes`);
  }

  /** Ends the hose being drawn; a hose of one point is removed. */
  finishHose(): void {
    const s = this.state;
    if (s === null || this.drawing === null) return;
    const i = this.drawing;
    const h = s.hoses[i];
    if (h !== undefined && h.points.length < 2) {
      this.change(() => {
        s.hoses.splice(i, 1);
        this.drawing = null;
        this.selectedHose = null;
      });
      this.say('a hose needs at least two points');
      return;
    }
    this.drawing = null;
    this.say(h ? `${h.name} finished: ${h.points.length} points` : '');
    this.redraw();
  }

  /** The authored hose nearest to `p` and the unit tangent there. */
  private nearestHose(p: Vec3): { hose: AuthorHose; tangent: Vec3; end: 'start' | 'end'; endDist: number } | null {
    let best: { hose: AuthorHose; tangent: Vec3; end: 'start' | 'end'; endDist: number } | null = null;
    let bestD = Infinity;
    for (const h of this.state?.hoses ?? []) {
      if (h.points.length < 2) continue;
      const pts = splineSamples(h.points);
      for (let i = 0; i + 1 < pts.length; i++) {
        const d = dist(pts[i], p);
        if (d < bestD) {
          bestD = d;
          const ds = dist(h.points[0], p);
          const de = dist(h.points[h.points.length - 1], p);
          best = { hose: h, tangent: unit(sub(pts[i + 1], pts[i])), end: ds <= de ? 'start' : 'end', endDist: Math.min(ds, de) };
        }
      }
    }
    return best;
  }

  /** A stub standing on the surface: base on it, mouth `length` out along the normal,
   *  axis (push-on, mouth → base) into the surface. Sized for the nearest hose end. */
  addStub(hit: SurfaceHit): void {
    const s = this.state;
    if (s === null) return;
    const length = 0.03;
    const mouth = add(hit.point, hit.normal, length);
    // the nearest end of an authored hose is the one meant to go on
    let end: { hose: AuthorHose; end: 'start' | 'end'; d: number } | null = null;
    for (const h of s.hoses) {
      if (h.points.length < 2) continue;
      for (const [which, q] of [['start', h.points[0]], ['end', h.points[h.points.length - 1]]] as const) {
        const d = dist(q, mouth);
        if (end === null || d < end.d) end = { hose: h, end: which, d };
      }
    }
    const sec = end ? this.hoseSection(end.hose) : this.currentSection();
    const diameter = Math.min(sec.d_inner + 0.002, (sec.d_inner + sec.d_outer) / 2);
    this.change(() => {
      s.stubs.push({
        name: this.uniqueName('stub', this.fastenerNames()),
        origin: mouth, axis: [-hit.normal[0], -hit.normal[1], -hit.normal[2]], length, diameter,
        hose: end?.hose.name ?? null, end: end?.end ?? 'end',
      });
    });
    this.say(`stub added on ${hit.part}${end ? ` for ${end.hose.name} (${end.end})` : ''}`);
  }

  /** A clip of the chosen type where a hose would rest on the surface: opening along the
   *  normal, its axis along the nearest hose (projected onto the surface). */
  addClip(hit: SurfaceHit): void {
    const s = this.state;
    if (s === null) return;
    const near = this.nearestHose(hit.point);
    const sec = near ? this.hoseSection(near.hose) : this.currentSection();
    const n = hit.normal;
    let l: Vec3 = near ? near.tangent : Math.abs(n[0]) < 0.9 ? cross(n, [1, 0, 0]) : cross(n, [0, 1, 0]);
    l = sub(l, [n[0] * dot(l, n), n[1] * dot(l, n), n[2] * dot(l, n)]);
    if (len(l) < 1e-6) l = Math.abs(n[0]) < 0.9 ? cross(n, [1, 0, 0]) : cross(n, [0, 1, 0]);
    l = unit(l);
    const type = (this.ui['author-clip-type'] as HTMLSelectElement).value as ClipType;
    this.change(() => {
      s.clips.push({
        name: this.uniqueName('clip', this.fastenerNames()),
        origin: add(hit.point, n, sec.d_outer / 2), opening: n, orientation: l, type,
        opening_width: sec.d_outer * 0.85, inner_diameter: sec.d_outer + 0.001,
        snap_force_n: type === 'cable_tie' ? 0 : 40, hose: near?.hose.name ?? null,
      });
    });
    this.say(`${type} clip added on ${hit.part}${near ? ` for ${near.hose.name}` : ''}`);
  }

  /** Moves a hose point, stub or clip to `p` (world frame): what a handle drag does. */
  moveTo(ref: HandleRef, p: Vec3): void {
    const s = this.state;
    if (s === null) return;
    this.change(() => this.place(ref, p));
  }

  private place(ref: HandleRef, p: Vec3): void {
    const s = this.state as AuthorState;
    if (ref.kind === 'hose') s.hoses[ref.i].points[ref.k] = p;
    else if (ref.kind === 'stub') s.stubs[ref.i].origin = p;
    else s.clips[ref.i].origin = p;
  }

  private commitDrag(): void {
    const obj = this.gizmo.object;
    const h = this.handles.find((x) => x.mesh === obj);
    if (h === undefined || this.state === null) return;
    const p: Vec3 = [obj!.position.x, obj!.position.y, obj!.position.z]; // parent = world frame
    this.place(h.ref, p);
    this.history.record(this.dragBefore);
    this.redraw();
  }

  deleteSelected(): void {
    const s = this.state;
    const ref = this.selected;
    if (s === null || ref === null) return;
    this.change(() => {
      if (ref.kind === 'hose') {
        const h = s.hoses[ref.i];
        h.points.splice(ref.k, 1);
        if (h.points.length < 2 && this.drawing !== ref.i) {
          s.hoses.splice(ref.i, 1);
          this.selectedHose = null;
          if (this.drawing !== null && this.drawing > ref.i) this.drawing--;
        }
      } else if (ref.kind === 'stub') s.stubs.splice(ref.i, 1);
      else s.clips.splice(ref.i, 1);
      this.selected = null;
    });
    this.gizmo.detach();
  }

  /** Starts from nothing: the base scene's hoses, stubs, clips and timeline go, its parts
   *  and settings stay; authored ones go too. */
  clear(): void {
    const s = this.state;
    if (s === null) return;
    this.change(() => {
      s.base.hoses = [];
      delete s.base.stubs;
      delete s.base.clips;
      delete s.base.timeline;
      s.hoses = [];
      s.stubs = [];
      s.clips = [];
      this.drawing = null;
      this.selectedHose = null;
      this.selected = null;
    });
    this.gizmo.detach();
    this.say('cleared: the parts stay; click a part surface to start a hose');
  }

  // ---------------------------------------------------------------- the file

  /** The scene document: the base scene with the authored hoses, stubs and clips, a
   *  leading `fix` for each hose whose start is fixed (author_document.ts). */
  document(name = this.input('author-name').value.trim() || 'authored'): Doc {
    const s = this.state;
    if (s === null) throw new Error('no scene document yet');
    return sceneDocument(s, name, this.unit);
  }

  /** The document as scene-file TOML. */
  toml(name?: string): string {
    const doc = this.document(name);
    return toToml(doc, 'Pliant scene authored in the viewer (docs/authoring.md)');
  }

  /** Downloads the scene file and sends it to the server to load and run. */
  save(): string {
    this.finishHose();
    const name = this.input('author-name').value.trim() || 'authored';
    let text: string;
    try {
      text = this.toml(name);
    } catch (e) {
      this.say(`cannot write the scene: ${(e as Error).message}`, true);
      return '';
    }
    this.lastToml = text;
    const file = `${name.replace(/[^\w.-]+/g, '_')}.toml`;
    this.lastSaveName = file;
    download(file, text);
    this.saving = true;
    this.net.send({ type: 'load_scene', text, format: 'toml', name: file });
    this.say(`saved ${file}; the server is loading it…`);
    return text;
  }

  /** The server's answer to a save: the loader's error (naming the field), shown here. */
  error(code: string, message: string): void {
    if (!this.saving || code !== 'invalid_scene') return;
    this.saving = false;
    this.say(`the loader refused the scene: ${message}`, true);
  }

  /** A new session started (after a save: the authored scene is running). */
  welcomed(scene: string): void {
    if (!this.saving) return;
    this.saving = false;
    this.say(`running '${scene}' (the file was downloaded too); keep editing and save again`);
  }

  // ---------------------------------------------------------------- drawing

  /** Rebuilds the previews: a translucent tube per hose, handles, stubs and clips. */
  redraw(): void {
    const attached = this.gizmo.object;
    const attachedRef = this.handles.find((h) => h.mesh === attached)?.ref ?? null;
    this.gizmo.detach();
    for (const c of [...this.group.children]) {
      this.group.remove(c);
      disposeTree(c);
    }
    this.handles = [];
    const s = this.state;
    this.updateSummary();
    if (s === null) return;
    const handleMat = (on: boolean) => new THREE.MeshBasicMaterial({ color: on ? 0xffe066 : 0xff8c1a, depthTest: false, transparent: true, opacity: 0.9 });
    s.hoses.forEach((h, i) => {
      const sec = this.hoseSection(h);
      const r = sec.d_outer / 2;
      if (h.points.length >= 2) {
        const curve = new THREE.CatmullRomCurve3(h.points.map((p) => new THREE.Vector3(...p)), false, 'catmullrom', 0.5);
        const tube = new THREE.Mesh(
          new THREE.TubeGeometry(curve, Math.max(8, (h.points.length - 1) * 16), r, 12, false),
          new THREE.MeshLambertMaterial({ color: i === this.selectedHose ? 0xffa040 : 0xd08030, transparent: true, opacity: 0.55 }),
        );
        tube.name = `author-hose:${h.name}`;
        this.group.add(tube);
      }
      h.points.forEach((p, k) => {
        const on = this.selected?.kind === 'hose' && this.selected.i === i && this.selected.k === k;
        const m = new THREE.Mesh(new THREE.SphereGeometry(Math.max(r * 0.7, 0.004), 12, 8), handleMat(on));
        m.position.set(...p);
        m.renderOrder = 10;
        m.name = `author-point:${h.name}:${k}`;
        this.group.add(m);
        this.handles.push({ mesh: m, ref: { kind: 'hose', i, k } });
      });
    });
    s.stubs.forEach((st, i) => {
      const f: FastenerData = { name: st.name, kind: 'stub', origin: st.origin, axis: unit(st.axis), opening: [0, 0, 0], length: st.length, diameter: st.diameter, opening_width: 0 };
      this.group.add(stubMesh(f));
      const m = new THREE.Mesh(new THREE.SphereGeometry(0.006, 12, 8), handleMat(this.selected?.kind === 'stub' && this.selected.i === i));
      m.position.set(...st.origin);
      m.renderOrder = 10;
      this.group.add(m);
      this.handles.push({ mesh: m, ref: { kind: 'stub', i } });
    });
    s.clips.forEach((c, i) => {
      const f: FastenerData = { name: c.name, kind: 'clip', origin: c.origin, axis: c.orientation, opening: c.opening, length: 0, diameter: c.inner_diameter, opening_width: c.opening_width };
      this.group.add(clipMesh(f));
      const m = new THREE.Mesh(new THREE.SphereGeometry(0.006, 12, 8), handleMat(this.selected?.kind === 'clip' && this.selected.i === i));
      m.position.set(...c.origin);
      m.renderOrder = 10;
      this.group.add(m);
      this.handles.push({ mesh: m, ref: { kind: 'clip', i } });
    });
    const want = this.selected ?? attachedRef;
    if (this.tool === 'move' && want !== null) {
      const h = this.handles.find((x) => JSON.stringify(x.ref) === JSON.stringify(want));
      if (h) this.gizmo.attach(h.mesh);
    }
  }

  private updateSummary(): void {
    const s = this.state;
    const el = this.ui['author-summary'];
    (this.ui['author-undo'] as HTMLButtonElement).disabled = !this.canUndo;
    (this.ui['author-redo'] as HTMLButtonElement).disabled = !this.canRedo;
    if (s === null) {
      el.textContent = '';
      return;
    }
    const baseHoses = Array.isArray(s.base.hoses) ? s.base.hoses.length : 0;
    const hs = s.hoses.map((h) => `${h.name} (${h.material}, ${h.points.length} pts)`).join(', ');
    el.textContent = `scene hoses kept: ${baseHoses}; new: ${hs || 'none'}; stubs: ${s.stubs.length}; clips: ${s.clips.length}`;
  }
}
