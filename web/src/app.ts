// The viewer as one object: the connection to `pliant serve`, the stage and its drawn
// session (parts, stubs, clips, hoses as force-coloured tubes, markers), the panel, the
// mouse and VR hands, and the mode — `live`, `replay` or `author` (app_mode.ts) — which
// decides what is drawn and who may act.

import * as THREE from 'three';
import { drawsLive, handsAct, nextMode, type Mode, type ModeEvent } from './app_mode';
import { Author } from './author';
import { beamValues, growAxialScale, legendRange, nodeColourValues, type ColourMode } from './colour_modes';
import { installDebugHandle } from './debug';
import { Envelopes } from './envelope';
import { findingRows, type FindingRow } from './findings';
import { MouseHand } from './grab';
import { HoseTube } from './hoses';
import { JunctionBodies } from './junction_bodies';
import { ForceLabels } from './labels';
import { Legend } from './legend';
import { ManikinView } from './manikin';
import { ViolationMarkers } from './markers';
import { Net } from './net';
import { Panel } from './panel';
import { PartControls } from './part_controls';
import { fastenerCarriers } from './part_joints';
import type { SceneSourceMessage, Snapshot, Welcome } from './protocol';
import { download, parseRecording, Player, Recorder } from './record';
import { Stage } from './scene';
import { XrHands } from './xr';

export class App {
  mode: Mode = 'live';
  readonly stage: Stage;
  readonly net: Net;
  readonly panel: Panel;
  readonly author: Author;
  readonly mouse: MouseHand;
  readonly xr: XrHands;
  readonly parts: PartControls;
  readonly manikin: ManikinView;
  private readonly legend: Legend;
  private readonly labels: ForceLabels;
  private readonly markers: ViolationMarkers;
  private readonly envelopes: Envelopes;
  private readonly recorder = new Recorder();
  /** What the hoses are coloured by, and the axial-force scale seen so far [N]. */
  readonly colouring = { mode: 'hand_load' as ColourMode, axialScale: 0 };
  /** Per hose, per node colour values (scratch). */
  private nodeValues: Float32Array[] = [];
  tubes: HoseTube[] = [];
  private bodies: JunctionBodies | null = null;
  /** The live session's welcome (and its text, for recordings). */
  private liveWelcome: Welcome | null = null;
  private liveWelcomeRaw = '';
  /** The welcome drawn: the live one, or the recording's in a replay. */
  shownWelcome: Welcome | null = null;
  /** The newest live snapshot, and the one drawn last. */
  latest: Snapshot | null = null;
  shown: Snapshot | null = null;
  private needsFraming = false;
  /** The recording replayed (in `replay` mode). */
  private player: Player | null = null;
  lastRecording = '';
  private lastRecordingShown = -1;
  /** The hose and part the finding clicked last names (indices; null: none). */
  private highlight: { hose: number | null; part: number | null } | null = null;
  readonly counters = { frames: 0, snapshots: 0, errors: [] as { code: string; message: string }[], reports: [] as string[] };

  constructor(root: HTMLElement, view: HTMLElement, readonly params: URLSearchParams) {
    this.stage = new Stage(view, params.get('quality') === 'low' ? 'low' : 'high');
    this.legend = new Legend(view);
    const url = App.socketUrl(params);
    this.net = new Net(url, {
      welcome: (w, raw) => this.welcomed(w, raw),
      snapshot: (s, raw) => this.snapshotReceived(s, raw),
      error: (e) => {
        this.counters.errors.push(e);
        if (this.counters.errors.length > 50) this.counters.errors.shift();
        this.panel.setMessage(`${e.code}: ${e.message}`, true);
        this.author.error(e.code, e.message);
      },
      sceneSource: (m) => this.sceneSource(m),
      report: (r) => {
        this.counters.reports.push(r.folder);
        const word = r.verdict.feasible === null ? 'not assessed' : r.verdict.feasible ? 'feasible so far' : 'NOT feasible';
        this.panel.setMessage(`report written: ${r.folder}/report.html (${word})`);
      },
      status: (text) => this.panel.setStatus(`${text} · ${url}`),
    });
    this.panel = new Panel(root, {
      pause: (p) => this.net.send({ type: p ? 'pause' : 'resume' }),
      step: (n) => this.net.send({ type: 'step', n }),
      reset: () => this.net.send({ type: 'reset' }),
      report: () => {
        this.panel.setMessage('writing the session report…');
        this.net.send({ type: 'report' });
      },
      ergonomics: (posture, population, duty) => this.net.send({ type: 'set_ergonomics', posture, population, duty }),
      openScene: (file) => {
        void file.text().then((text) => {
          const json = file.name.toLowerCase().endsWith('.json');
          this.panel.setMessage(`loading ${file.name}…`);
          this.net.send({ type: 'load_scene', text, format: json ? 'json' : 'toml', name: file.name });
        });
      },
      record: (on) => {
        if (on) {
          if (this.liveWelcomeRaw === '') return;
          this.recorder.begin(this.liveWelcomeRaw);
          this.panel.setRecording(true, 0);
        } else {
          this.stopRecording();
        }
      },
      replayFile: (file) => void file.text().then((text) => this.startReplay(text)),
      live: () => this.change('live'),
      author: () => this.change('toggle_author'),
      colourMode: (mode) => this.setColourMode(mode),
      grip: (g) => {
        this.mouse.grip = g;
      },
      envelopeFile: (file) =>
        void file.arrayBuffer().then((buf) => this.showEnvelope(this.envelopes.load(buf, file.name), file.name)),
      envelopeVisible: (on) => {
        this.envelopes.visible = on;
      },
      envelopeClear: () => {
        this.envelopes.clear();
        this.panel.setEnvelopes([], false);
      },
      finding: (row) => this.focusFinding(row),
    });
    this.envelopes = new Envelopes(this.stage);
    this.envelopes.acceptDrops(view, (message, error) => {
      this.panel.setEnvelopes(this.envelopes.loaded.map((e) => e.name), this.envelopes.visible);
      this.panel.setMessage(message, error);
    });
    const envelopeUrl = params.get('envelope');
    if (envelopeUrl !== null) void this.showEnvelope(this.envelopes.loadUrl(envelopeUrl), envelopeUrl);
    this.markers = new ViolationMarkers(this.stage);
    this.author = new Author(this.stage, this.net, this.panel.authorSlot, {
      changed: (on) => {
        this.panel.setAuthoring(on);
        if (on) this.mouse.drop();
      },
    });
    this.parts = new PartControls(this.stage, this.net, this.panel.partsSlot);
    this.manikin = new ManikinView(this.panel.workerSlot);
    this.stage.world.add(this.manikin.group);
    this.panel.replayPlay.onclick = () => {
      if (this.player === null) return;
      this.player.setPlaying(!this.player.playing, performance.now());
      this.panel.replayPlay.textContent = this.player.playing ? 'Pause' : 'Play';
    };
    this.panel.replaySlider.oninput = () => {
      if (this.player !== null) this.player.seek(Number(this.panel.replaySlider.value) / 1000, performance.now());
    };
    this.mouse = new MouseHand(this.stage, () => this.tubes, this.net, () => handsAct(this.mode) && !this.parts.onHandle);
    this.xr = new XrHands(this.stage, this.net, view);
    this.labels = new ForceLabels(this.stage);
    this.stage.renderer.setAnimationLoop(() => this.frame());
    installDebugHandle(this);
  }

  /** The WebSocket of the server that served the page (`?ws=` another); the page URL
   *  `pliant serve` prints carries `?token=…` when the server requires one. */
  private static socketUrl(params: URLSearchParams): string {
    const token = params.get('token');
    return (
      params.get('ws') ??
      `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws` +
        (token ? `?token=${encodeURIComponent(token)}` : '')
    );
  }

  start(): void {
    this.net.connect();
  }

  /** Changes the mode (app_mode.ts) and does what leaving and entering it takes. */
  change(event: ModeEvent): void {
    const from = this.mode;
    const to = nextMode(from, event);
    if (from === 'replay' && to !== 'replay') {
      this.player = null;
      this.panel.setReplay(false);
      if (this.liveWelcome !== null) this.showWelcome(this.liveWelcome);
      this.panel.setMessage('live');
    }
    if (from === 'author' && to !== 'author') this.author.toggle(false);
    this.mode = to;
    if (to === 'author' && from !== 'author') this.author.toggle(true);
    if (to === 'replay') this.panel.setReplay(true);
    this.parts.setEnabled(handsAct(to));
  }

  get replaying(): boolean {
    return this.mode === 'replay';
  }

  private welcomed(w: Welcome, raw: string): void {
    const newScene = this.liveWelcome !== null;
    this.liveWelcome = w;
    this.liveWelcomeRaw = raw;
    this.mouse.handId = w.client_id * 4;
    this.xr.handBase = w.client_id * 4;
    this.xr.worker = w.session.worker !== undefined;
    this.mouse.drop();
    this.xr.drop();
    this.latest = null;
    if (this.recorder.active) this.stopRecording();
    if (drawsLive(this.mode)) this.showWelcome(w);
    this.panel.setMessage(newScene ? `loaded scene '${w.session.scene}'` : '');
    this.author.welcomed(w.session.scene);
  }

  private snapshotReceived(s: Snapshot, raw: string): void {
    this.counters.snapshots++;
    if (this.latest !== null && s.epoch !== this.latest.epoch) {
      this.mouse.drop();
      this.xr.drop();
    }
    this.latest = s;
    this.recorder.add(raw);
  }

  private sceneSource(m: SceneSourceMessage): void {
    this.author.source(m);
  }

  private showWelcome(w: Welcome): void {
    for (const t of this.tubes) {
      this.stage.world.remove(t.mesh);
      t.dispose();
    }
    this.tubes = w.session.hoses.map((h, i) => new HoseTube(h, i));
    this.nodeValues = this.tubes.map((t) => new Float32Array(t.nodes));
    this.colouring.axialScale = 0;
    this.markers.clear();
    for (const t of this.tubes) this.stage.world.add(t.mesh);
    if (this.bodies !== null) {
      this.stage.world.remove(this.bodies.group);
      this.bodies.dispose();
    }
    this.bodies = new JunctionBodies(w.session.junction_bodies ?? [], w.session.hoses.map((h) => h.radii));
    this.stage.world.add(this.bodies.group);
    this.shownWelcome = w;
    this.shown = null;
    this.needsFraming = true;
    this.highlight = null;
    this.panel.welcome(w);
    this.parts.welcome(w.session.parts);
    this.manikin.welcome(w.session.worker);
    this.stage.setFastenerCarriers(fastenerCarriers(w.session.fasteners ?? []));
  }

  private stopRecording(): void {
    const n = this.recorder.count;
    const text = this.recorder.finish();
    this.panel.setRecording(false);
    download(`pliant-recording-${new Date().toISOString().replace(/[:.]/g, '-')}.json`, text);
    this.panel.setMessage(`recording saved (${n} snapshots)`);
    this.lastRecording = text;
  }

  startReplay(text: string): void {
    try {
      const rec = parseRecording(text);
      this.change('replay');
      this.player = new Player(rec);
      this.mouse.drop();
      this.showWelcome(rec.welcome);
      this.panel.replayPlay.textContent = 'Pause';
      this.panel.setMessage(`replaying ${rec.frames.length} snapshots (${this.player.duration.toFixed(1)} s)`);
    } catch (e) {
      this.panel.setMessage(`cannot replay: ${(e as Error).message}`, true);
    }
  }

  private showEnvelope(loading: Promise<number>, name: string): Promise<void> {
    return loading
      .then((n) => {
        this.panel.setEnvelopes(this.envelopes.loaded.map((e) => e.name), this.envelopes.visible);
        this.panel.setMessage(`envelope ${name}: ${n} mesh(es) shown`);
      })
      .catch((e: Error) => this.panel.setMessage(`cannot show the envelope ${name}: ${e.message}`, true));
  }

  setColourMode(mode: ColourMode): void {
    this.colouring.mode = mode;
    this.panel.colourMode.value = mode;
    if (this.shown !== null) this.apply(this.shown);
  }

  /** The violation markers shown (hose:check, world position). */
  markerPositions(): ReturnType<ViolationMarkers['positions']> {
    return this.markers.positions();
  }

  /** Tolerance envelopes shown: file names, visibility, mesh count. */
  envelopeState(): { loaded: { name: string; meshes: number }[]; visible: boolean; meshes: number } {
    return { loaded: [...this.envelopes.loaded], visible: this.envelopes.visible, meshes: this.envelopes.group.children.length };
  }

  /** A finding clicked in the panel: its hose or part lights up (until another finding
   *  is clicked, or this one again), and a replay goes to its time. */
  focusFinding(row: FindingRow): void {
    const same = this.highlight !== null && this.highlight.hose === row.hose && this.highlight.part === row.part;
    this.highlight = same ? null : { hose: row.hose, part: row.part };
    if (this.player !== null && row.time !== null) this.player.seekSimulated(row.time, performance.now());
    this.showHighlight();
  }

  private showHighlight(): void {
    const h = this.highlight;
    this.tubes.forEach((t, i) => t.setHighlighted(h !== null && h.hose === i));
    this.stage.highlightPart(h?.part ?? null);
  }

  /** The findings of the drawn snapshot's verdict, as the panel lists them. */
  findings(): FindingRow[] {
    const f = this.shown?.verdict?.findings;
    const w = this.shownWelcome;
    if (f === undefined || w === null) return [];
    return findingRows(f, w.session.hoses.map((h) => h.name), w.session.parts.map((p) => p.name));
  }

  private apply(s: Snapshot): void {
    if (this.needsFraming && this.shownWelcome !== null) {
      this.needsFraming = false;
      const box = new THREE.Box3();
      for (const h of s.hoses) for (const p of h.positions) box.expandByPoint(new THREE.Vector3(...p));
      this.stage.load(this.shownWelcome.session, box);
      this.showHighlight();
      if (this.xr.inSession) this.xr.place(true);
    }
    this.stage.setPartPoses(s.part_poses ?? []);
    this.parts.update(s.part_poses ?? []);
    this.colouring.axialScale = growAxialScale(this.colouring.axialScale, s.hoses);
    const range = legendRange(this.colouring.mode, this.shownWelcome?.session.twist_limit, this.colouring.axialScale);
    this.legend.show(range);
    s.hoses.forEach((h, i) => {
      const t = this.tubes[i];
      if (t === undefined) return;
      const beams = beamValues(this.colouring.mode, h);
      const values = beams === null ? null : nodeColourValues(range, beams, this.nodeValues[i]);
      t.update(h.positions, h.colour, values);
    });
    this.bodies?.update((h, i) => (this.tubes[h] !== undefined && i < this.tubes[h].nodes ? this.tubes[h].node(i) : null));
    this.markers.update(s.checks ?? [], (h) => this.tubes[h]?.positions ?? [], (h) => this.tubes[h]?.maxRadius ?? 0);
    this.labels.update(s.hands);
    if (this.shownWelcome !== null) {
      const session = this.shownWelcome.session;
      this.manikin.update(s.worker, { parts: session.parts.map((p) => p.name), hoses: session.hoses.map((h) => h.name) });
    }
    this.shown = s;
    this.panel.snapshot(s, this.findings());
  }

  private frame(): void {
    const now = performance.now();
    let drewLive = false;
    if (drawsLive(this.mode)) {
      if (this.latest !== null && this.latest !== this.shown) {
        this.apply(this.latest);
        drewLive = true;
      }
    } else if (this.player !== null) {
      const s = this.player.frame(now);
      if (s !== null && s !== this.shown) this.apply(s);
      const d = this.player.duration;
      if (d > 0) this.panel.replaySlider.value = String(Math.round((this.player.time(now) / d) * 1000));
    }
    this.manikin.tick(now);
    this.mouse.flush();
    this.xr.update();
    this.stage.renderer.render(this.stage.scene, this.stage.camera);
    this.counters.frames++;
    if (drewLive) this.net.frameDrawn(performance.now());
    if (this.recorder.active && this.recorder.count !== this.lastRecordingShown && this.counters.frames % 15 === 0) {
      this.lastRecordingShown = this.recorder.count;
      this.panel.setRecording(true, this.recorder.count);
    }
  }
}
