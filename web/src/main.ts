// Pliant's browser/VR viewer (issue 4): connects to the `pliant serve` that served this
// page, draws the session (parts, stubs, clips, hoses as force-coloured tubes), lets the
// mouse or VR controllers grab and move hoses, and shows loads, limits and the verdict.
// Colour modes with a legend (hand load, bend radius vs minimum, twist, axial force),
// markers at the installation checks' violations, tolerance envelopes (dropped files or
// `?envelope=URL`). `?xr=emulate` installs an emulated headset (iwer) for tests and
// development.

import './style.css';
import * as THREE from 'three';
import { Author } from './author';
import { beamValues, growAxialScale, legendRange, nodeColourValues, type ColourMode } from './colour_modes';
import { installDebugHandle } from './debug';
import { Envelopes } from './envelope';
import { MouseHand } from './grab';
import { HoseTube } from './hoses';
import { JunctionBodies } from './junction_bodies';
import { ForceLabels } from './labels';
import { Legend } from './legend';
import { ViolationMarkers } from './markers';
import { Net } from './net';
import { Panel } from './panel';
import type { Snapshot, Welcome } from './protocol';
import { download, parseRecording, Player, Recorder } from './record';
import { Stage } from './scene';
import { XrHands } from './xr';

async function main(): Promise<void> {
  const params = new URLSearchParams(location.search);
  if (params.get('xr') === 'emulate') {
    const { XRDevice, metaQuest3 } = await import('iwer');
    const device = new XRDevice(metaQuest3);
    device.installRuntime({ forceInstall: true });
    (window as unknown as { pliantXrDevice: unknown }).pliantXrDevice = device;
  }

  const app = document.getElementById('app') as HTMLElement;
  const view = document.getElementById('view') as HTMLElement;
  const stage = new Stage(view, params.get('quality') === 'low' ? 'low' : 'high');
  const legend = new Legend(view);
  /** What the hoses are coloured by, and the axial-force scale seen so far [N]. */
  const colouring = { mode: 'hand_load' as ColourMode, axialScale: 0 };
  let nodeValues: Float32Array[] = []; // per hose, per node colour values (scratch)

  let tubes: HoseTube[] = [];
  let bodies: JunctionBodies | null = null;
  let liveWelcome: Welcome | null = null;
  let liveWelcomeRaw = '';
  let shownWelcome: Welcome | null = null;
  let latest: Snapshot | null = null; // newest live snapshot
  let shown: Snapshot | null = null; // the one drawn last
  let needsFraming = false;
  let player: Player | null = null;
  const recorder = new Recorder();
  const state = { frames: 0, snapshots: 0, errors: [] as { code: string; message: string }[], reports: [] as string[] };

  // the page URL `pliant serve` prints carries ?token=… when the server requires one
  // (bound to the network, or --token): the WebSocket passes it on
  const token = params.get('token');
  const wsUrl =
    params.get('ws') ??
    `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws` +
      (token ? `?token=${encodeURIComponent(token)}` : '');

  const showWelcome = (w: Welcome) => {
    for (const t of tubes) {
      stage.world.remove(t.mesh);
      t.dispose();
    }
    tubes = w.session.hoses.map((h, i) => new HoseTube(h, i));
    nodeValues = tubes.map((t) => new Float32Array(t.nodes));
    colouring.axialScale = 0;
    markers.clear();
    for (const t of tubes) stage.world.add(t.mesh);
    if (bodies !== null) {
      stage.world.remove(bodies.group);
      bodies.dispose();
    }
    bodies = new JunctionBodies(w.session.junction_bodies ?? [], w.session.hoses.map((h) => h.radii));
    stage.world.add(bodies.group);
    shownWelcome = w;
    shown = null;
    needsFraming = true;
    panel.welcome(w);
  };

  const net = new Net(wsUrl, {
    welcome(w, raw) {
      const newScene = liveWelcome !== null;
      liveWelcome = w;
      liveWelcomeRaw = raw;
      mouse.handId = w.client_id * 4;
      xr.handBase = w.client_id * 4;
      mouse.drop();
      xr.drop();
      latest = null;
      if (recorder.active) stopRecording();
      if (player === null) showWelcome(w);
      panel.setMessage(newScene ? `loaded scene '${w.session.scene}'` : '');
      author.welcomed(w.session.scene);
    },
    snapshot(s, raw) {
      state.snapshots++;
      if (latest !== null && s.epoch !== latest.epoch) {
        mouse.drop();
        xr.drop();
      }
      latest = s;
      recorder.add(raw);
    },
    error(e) {
      state.errors.push(e);
      if (state.errors.length > 50) state.errors.shift();
      panel.setMessage(`${e.code}: ${e.message}`, true);
      author.error(e.code, e.message);
    },
    sceneSource(m) {
      author.source(m);
    },
    report(r) {
      state.reports.push(r.folder);
      const word = r.verdict.feasible === null ? 'not assessed' : r.verdict.feasible ? 'feasible so far' : 'NOT feasible';
      panel.setMessage(`report written: ${r.folder}/report.html (${word})`);
    },
    status(text) {
      panel.setStatus(`${text} · ${wsUrl}`);
    },
  });

  const stopRecording = () => {
    const n = recorder.count;
    const text = recorder.finish();
    panel.setRecording(false);
    download(`pliant-recording-${new Date().toISOString().replace(/[:.]/g, '-')}.json`, text);
    panel.setMessage(`recording saved (${n} snapshots)`);
    lastRecording = text;
  };
  let lastRecording = '';

  const startReplay = (text: string) => {
    try {
      const rec = parseRecording(text);
      player = new Player(rec);
      mouse.drop();
      showWelcome(rec.welcome);
      panel.setReplay(true);
      panel.replayPlay.textContent = 'Pause';
      panel.setMessage(`replaying ${rec.frames.length} snapshots (${player.duration.toFixed(1)} s)`);
    } catch (e) {
      panel.setMessage(`cannot replay: ${(e as Error).message}`, true);
    }
  };
  const stopReplay = () => {
    player = null;
    panel.setReplay(false);
    if (liveWelcome !== null) showWelcome(liveWelcome);
    panel.setMessage('live');
  };

  const panel = new Panel(app, {
    pause: (p) => net.send({ type: p ? 'pause' : 'resume' }),
    step: (n) => net.send({ type: 'step', n }),
    reset: () => net.send({ type: 'reset' }),
    report: () => {
      panel.setMessage('writing the session report…');
      net.send({ type: 'report' });
    },
    ergonomics: (posture, population, duty) => net.send({ type: 'set_ergonomics', posture, population, duty }),
    openScene: (file) => {
      void file.text().then((text) => {
        const json = file.name.toLowerCase().endsWith('.json');
        panel.setMessage(`loading ${file.name}…`);
        net.send({ type: 'load_scene', text, format: json ? 'json' : 'toml', name: file.name });
      });
    },
    record: (on) => {
      if (on) {
        if (liveWelcomeRaw === '') return;
        recorder.begin(liveWelcomeRaw);
        panel.setRecording(true, 0);
      } else {
        stopRecording();
      }
    },
    replayFile: (file) => void file.text().then(startReplay),
    live: stopReplay,
    author: () => author.toggle(),
    colourMode: (mode) => setColourMode(mode),
    grip: (g) => {
      mouse.grip = g;
    },
    envelopeFile: (file) =>
      void file.arrayBuffer().then((buf) => showEnvelope(envelopes.load(buf, file.name), file.name)),
    envelopeVisible: (on) => {
      envelopes.visible = on;
    },
    envelopeClear: () => {
      envelopes.clear();
      panel.setEnvelopes([], false);
    },
  });
  const envelopes = new Envelopes(stage);
  const showEnvelope = (loading: Promise<number>, name: string) =>
    loading
      .then((n) => {
        panel.setEnvelopes(envelopes.loaded.map((e) => e.name), envelopes.visible);
        panel.setMessage(`envelope ${name}: ${n} mesh(es) shown`);
      })
      .catch((e: Error) => panel.setMessage(`cannot show the envelope ${name}: ${e.message}`, true));
  envelopes.acceptDrops(view, (message, error) => {
    panel.setEnvelopes(envelopes.loaded.map((e) => e.name), envelopes.visible);
    panel.setMessage(message, error);
  });
  const envelopeUrl = params.get('envelope');
  if (envelopeUrl !== null) void showEnvelope(envelopes.loadUrl(envelopeUrl), envelopeUrl);
  const markers = new ViolationMarkers(stage);
  const setColourMode = (mode: ColourMode) => {
    colouring.mode = mode;
    panel.colourMode.value = mode;
    if (shown !== null) apply(shown);
  };
  const author = new Author(stage, net, panel.authorSlot, {
    changed: (on) => {
      panel.setAuthoring(on);
      if (on) mouse.drop();
    },
  });
  panel.replayPlay.onclick = () => {
    if (player === null) return;
    player.setPlaying(!player.playing, performance.now());
    panel.replayPlay.textContent = player.playing ? 'Pause' : 'Play';
  };
  panel.replaySlider.oninput = () => {
    if (player !== null) player.seek(Number(panel.replaySlider.value) / 1000, performance.now());
  };

  const mouse = new MouseHand(stage, () => tubes, net, () => player === null && !author.active);
  const xr = new XrHands(stage, net, view);
  const labels = new ForceLabels(stage);

  const apply = (s: Snapshot) => {
    stage.setPartPoses(s.part_poses ?? []);
    colouring.axialScale = growAxialScale(colouring.axialScale, s.hoses);
    const range = legendRange(colouring.mode, shownWelcome?.session.twist_limit, colouring.axialScale);
    legend.show(range);
    s.hoses.forEach((h, i) => {
      const t = tubes[i];
      if (t === undefined) return;
      const beams = beamValues(colouring.mode, h);
      const values = beams === null ? null : nodeColourValues(range, beams, nodeValues[i]);
      t.update(h.positions, h.colour, values);
    });
    bodies?.update((h, i) => (tubes[h] !== undefined && i < tubes[h].nodes ? tubes[h].node(i) : null));
    markers.update(s.checks ?? [], (h) => tubes[h]?.positions ?? [], (h) => tubes[h]?.maxRadius ?? 0);
    labels.update(s.hands);
    panel.snapshot(s);
    if (needsFraming && shownWelcome !== null) {
      needsFraming = false;
      const box = new THREE.Box3();
      for (const h of s.hoses) for (const p of h.positions) box.expandByPoint(new THREE.Vector3(...p));
      stage.load(shownWelcome.session, box);
      if (xr.inSession) xr.place(true);
    }
    shown = s;
  };

  let lastRecordingShown = -1;
  stage.renderer.setAnimationLoop(() => {
    const now = performance.now();
    let drewLive = false;
    if (player !== null) {
      const s = player.frame(now);
      if (s !== null && s !== shown) apply(s);
      const d = player.duration;
      if (d > 0) panel.replaySlider.value = String(Math.round((player.time(now) / d) * 1000));
    } else if (latest !== null && latest !== shown) {
      apply(latest);
      drewLive = true;
    }
    mouse.flush();
    xr.update();
    stage.renderer.render(stage.scene, stage.camera);
    state.frames++;
    if (drewLive) net.frameDrawn(performance.now());
    if (recorder.active && recorder.count !== lastRecordingShown && state.frames % 15 === 0) {
      lastRecordingShown = recorder.count;
      panel.setRecording(true, recorder.count);
    }
  });

  installDebugHandle({
    stage,
    net,
    mouse,
    xr,
    state,
    tubes: () => tubes,
    latest: () => latest,
    shown: () => shown,
    welcome: () => shownWelcome,
    replaying: () => player !== null,
    startReplay,
    lastRecording: () => lastRecording,
    author,
    colouring,
    setColourMode,
    markers,
    envelopes,
  });
  net.connect();
}

void main();
