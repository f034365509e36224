// `window.pliant`: a small debug handle for tests, benchmarks and the browser console —
// the newest snapshot, hose node positions, screen coordinates of world points, latency
// samples. Read-only views plus `send` for raw protocol messages.

import * as THREE from 'three';
import type { App } from './app';
import type { ColourMode } from './colour_modes';
import type { FindingRow } from './findings';
import type { Grip } from './grips';
import type { ManikinCapsule } from './manikin_model';
import type { ClientMessage, Vec3 } from './protocol';

export function installDebugHandle(app: App): void {
  const src = {
    stage: app.stage,
    net: app.net,
    mouse: app.mouse,
    xr: app.xr,
    author: app.author,
    colouring: app.colouring,
    state: app.counters,
  };
  const handle = {
    get frames() { return src.state.frames; },
    get snapshots() { return src.state.snapshots; },
    get errors() { return src.state.errors; },
    get reports() { return src.state.reports; },
    get connected() { return src.net.open; },
    get clientId() { return src.net.clientId; },
    get welcome() { return app.shownWelcome; },
    get snapshot() { return app.latest; },
    get shown() { return app.shown; },
    get replaying() { return app.replaying; },
    /** The mode: live, replay or author (app_mode.ts). */
    get mode() { return app.mode; },
    get mouseHandId() { return src.mouse.handId; },
    get lastPick() { return src.mouse.lastPick; },
    get xrHandIds() { return src.xr.hands.map((h) => src.xr.handBase + h.handId); },
    get inVr() { return src.xr.inSession; },
    get xrMode() { return src.xr.mode; },
    get xrHitTest() { return src.xr.hitTest; },
    /** AR: stands the scene on a real surface at `hit` (three.js space), as select on the reticle does. */
    xrStandOn(hit: [number, number, number]) { src.xr.standOn(hit); },
    /** The worker drawn: shown or not, its capsules (manikin_model.ts), the panel's lines,
     *  and a seated worker's seat box (shown or not, its centre and its full lengths along
     *  the worker's forward, left and up, in the scene's frame). */
    manikin(): { visible: boolean; capsules: ManikinCapsule[]; lines: string[]; seat: { visible: boolean; centre: number[]; size: number[] } } {
      const lines = [...document.querySelectorAll('#worker div')].map((d) => d.textContent ?? '');
      return { visible: app.manikin.group.visible, capsules: app.manikin.drawn, lines, seat: app.manikin.seatDrawn() };
    },
    /** The scene's lowest height in three.js space (y up; in AR, the real floor is 0) and
     *  whether its own background is drawn. */
    get sceneLowest(): number { return new THREE.Box3().setFromObject(src.stage.world).min.y; },
    get backgroundShown(): boolean { return src.stage.scene.background !== null; },
    /** The colour mode and the axial-force legend's scale [N]; `setColourMode`. */
    get colourMode() { return src.colouring.mode; },
    get axialScale() { return src.colouring.axialScale; },
    setColourMode(mode: ColourMode): void { app.setColourMode(mode); },
    /** Per-vertex colours of hose `h`'s tube (linear RGB, flattened). */
    tubeColours(h: number): number[] {
      const a = app.tubes[h]?.mesh.geometry.getAttribute('color');
      return a === undefined ? [] : Array.from(a.array as Float32Array);
    },
    /** The violation markers shown (hose:check, world position). */
    markers(): { key: string; position: Vec3 }[] { return app.markerPositions(); },
    /** The mouse's grip choice; each controller's grip; cycle controller i's. */
    get mouseGrip(): Grip { return src.mouse.grip; },
    get xrGripChoices(): Grip[] { return src.xr.hands.map((h) => h.hold); },
    cycleXrGrip(i: number): Grip | null { return src.xr.cycleGrip(i); },
    /** Tolerance envelopes shown: file names and mesh counts, visibility. */
    get envelopes() { return app.envelopeState(); },
    /** Each part's drawn transform (world frame): where its reference origin went and
     *  its rotation [x, y, z, w] — the part's pose. */
    partPoses(): { translation: Vec3; rotation: [number, number, number, number] }[] {
      return src.stage.partMeshes().map((m) => ({
        translation: [m.position.x, m.position.y, m.position.z],
        rotation: [m.quaternion.x, m.quaternion.y, m.quaternion.z, m.quaternion.w],
      }));
    },
    /** The objects drawn in the world frame whose name starts with `prefix` (e.g.
     *  `protection:`, `junction:`): name, visibility, the centre of their drawn vertices
     *  (world frame) and how many there are. */
    objects(prefix: string): { name: string; visible: boolean; centre: Vec3; vertices: number }[] {
      const out: { name: string; visible: boolean; centre: Vec3; vertices: number }[] = [];
      src.stage.world.updateMatrixWorld(true);
      const toWorld = src.stage.world.matrixWorld.clone().invert();
      src.stage.world.traverse((o) => {
        if (!o.name.startsWith(prefix) || !(o instanceof THREE.Mesh)) return;
        const box = new THREE.Box3().setFromObject(o, true).applyMatrix4(toWorld);
        const c = box.getCenter(new THREE.Vector3());
        const n = (o.geometry as THREE.BufferGeometry).getAttribute('position')?.count ?? 0;
        out.push({ name: o.name, visible: o.visible, centre: [c.x, c.y, c.z], vertices: n });
      });
      return out;
    },
    /** Points the camera at world point `p` from `distance` metres away. */
    lookAt(p: Vec3, distance: number): void {
      const t = src.stage.toThree(p);
      src.stage.controls.target.copy(t);
      src.stage.camera.position.copy(t).add(new THREE.Vector3(0.6, 0.5, 0.6).multiplyScalar(distance));
      src.stage.controls.update();
    },
    /** Node positions of hose `h` as drawn (world frame). */
    hoseNodes(h: number): Vec3[] {
      const t = app.tubes[h];
      if (t === undefined) return [];
      return Array.from({ length: t.nodes }, (_, i) => t.node(i));
    },
    /** Client (CSS pixel) coordinates of a world point. */
    screenOf(p: Vec3): { x: number; y: number } {
      const v = src.stage.toThree(p).project(src.stage.camera);
      const r = src.stage.renderer.domElement.getBoundingClientRect();
      return { x: r.left + ((v.x + 1) / 2) * r.width, y: r.top + ((1 - v.y) / 2) * r.height };
    },
    /** three.js (= XR reference space) coordinates of a world point. */
    threeOf(p: Vec3): Vec3 {
      const v = src.stage.toThree(p);
      return [v.x, v.y, v.z];
    },
    /** Each controller grip's position in three.js space, and whether it holds a hose. */
    xrGrips(): { position: Vec3; held: boolean; handId: number }[] {
      return src.xr.hands.map((h) => {
        const v = h.grip.getWorldPosition(h.grip.position.clone());
        return { position: [v.x, v.y, v.z], held: h.held, handId: src.xr.handBase + h.handId };
      });
    },
    /** Latency samples: ms from sending a move to its snapshot and to the frame drawn. */
    latency(): { snapshot: number; frame: number }[] {
      return src.net.done
        .filter((p) => p.snapshotAt !== undefined && p.frameAt !== undefined)
        .map((p) => ({ snapshot: (p.snapshotAt as number) - p.sentAt, frame: (p.frameAt as number) - p.sentAt }));
    },
    clearLatency(): void {
      src.net.done.length = 0;
      src.net.pending.length = 0;
    },
    send(msg: ClientMessage): boolean {
      return src.net.send(msg);
    },
    replay(text: string): void {
      app.startReplay(text);
    },
    get lastRecording() { return app.lastRecording; },
    /** The moving parts' rows: joint coordinate (deg or m) and slider position. */
    partControls() { return app.parts.shown(); },
    /** The last move a slider or handle sent; client coordinates of points on the part
     *  handle named `axis` ("Z": a hinge's ring, "X": a slide's arrow). */
    get lastPartMove() { return app.parts.lastMove; },
    get partHandleHovered() { return app.parts.onHandle; },
    partHandlePoints(axis: string): { x: number; y: number }[] {
      const r = src.stage.renderer.domElement.getBoundingClientRect();
      return app.parts.handlePoints(axis).map((v) => {
        const p = v.project(src.stage.camera);
        return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
      });
    },
    /** The stubs, connectors and clips as drawn (world frame). */
    fasteners() { return app.stage.fastenersDrawn(); },
    /** The verdict's findings as listed; `focusFinding(i)` does what a click on row i does. */
    findings(): FindingRow[] { return app.findings(); },
    focusFinding(i: number): void { const r = app.findings()[i]; if (r !== undefined) app.focusFinding(r); },
    /** Whether hose h / part k is drawn highlighted. */
    highlighted(): { hoses: number[]; parts: number[] } {
      const glow = (m: THREE.Mesh) => (m.material as THREE.MeshLambertMaterial).emissive.getHex() !== 0;
      return {
        hoses: app.tubes.flatMap((t, i) => (glow(t.mesh) ? [i] : [])),
        parts: app.stage.partMeshes().flatMap((m, i) => (glow(m) ? [i] : [])),
      };
    },
    /** Scene authoring: the mode's state, the document's TOML, undo/redo depth, and
     *  `moveTo` (what a handle drag does). */
    author: {
      get active() { return src.author.active; },
      get tool() { return src.author.tool; },
      get state() { return src.author.state; },
      get canUndo() { return src.author.canUndo; },
      get canRedo() { return src.author.canRedo; },
      get lastToml() { return src.author.lastToml; },
      toml(): string { return src.author.toml(); },
      points(h: number): Vec3[] { return src.author.state?.hoses[h]?.points ?? []; },
      movePoint(h: number, k: number, p: Vec3): void { src.author.moveTo({ kind: 'hose', i: h, k }, p); },
    },
    canvasPixels(): { width: number; height: number; data: number[] } {
      const gl = src.stage.renderer.getContext();
      const w = gl.drawingBufferWidth;
      const h = gl.drawingBufferHeight;
      const buf = new Uint8Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, buf);
      return { width: w, height: h, data: Array.from(buf) };
    },
  };
  (window as unknown as { pliant: typeof handle }).pliant = handle;
}
