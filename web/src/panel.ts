// The side panel: session status, controls (pause/step/reset, ergonomic profile, open a
// scene, record/replay), each hand's force and torque against its limit (bars and a live
// plot), stub and clip forces, the installation checks' violations and the running
// verdict; the colour mode, the mouse's grip and tolerance envelopes to show.

import { colourCss } from './colour';
import { COLOUR_MODES, type ColourMode } from './colour_modes';
import { GRIPS, gripLabel, type Grip } from './grips';
import { violationText, type FindingRow } from './findings';
import { LoadPlot } from './plot';
import { norm, type Snapshot, type Welcome } from './protocol';

/** A new element with attributes and text. */
export function el<K extends keyof HTMLElementTagNameMap>(tag: K, attrs: Record<string, string> = {}, text?: string): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function bar(ratio: number | null | undefined): HTMLElement {
  const outer = el('div', { class: 'bar' });
  const inner = el('div', { class: 'fill' });
  const r = ratio ?? 0;
  inner.style.width = `${Math.min(r, 1.5) / 1.5 * 100}%`;
  inner.style.background = colourCss(ratio ?? 0);
  const limit = el('div', { class: 'limit' });
  limit.style.left = `${100 / 1.5}%`;
  outer.append(inner, limit);
  return outer;
}

const fmt = (x: number | null | undefined, digits = 1) => (x === null || x === undefined || !Number.isFinite(x) ? '–' : x.toFixed(digits));

export interface PanelActions {
  pause(paused: boolean): void;
  step(n: number): void;
  reset(): void;
  report(): void;
  ergonomics(posture: string, population: string, duty: string): void;
  openScene(file: File): void;
  record(on: boolean): void;
  replayFile(file: File): void;
  live(): void;
  author(): void;
  colourMode(mode: ColourMode): void;
  grip(grip: Grip): void;
  envelopeFile(file: File): void;
  envelopeVisible(on: boolean): void;
  envelopeClear(): void;
  /** A finding of the verdict clicked: highlight what it names, go to its time. */
  finding(row: FindingRow): void;
}

export class Panel {
  readonly root: HTMLElement;
  private readonly status = el('div', { id: 'status' });
  private readonly scene = el('div', { id: 'scene-name' });
  private readonly clock = el('div', { id: 'clock' });
  private readonly hands = el('div', { id: 'hands' });
  private readonly fasteners = el('div', { id: 'fasteners' });
  private readonly verdict = el('div', { id: 'verdict' });
  private readonly checks = el('div', { id: 'checks' });
  readonly colourMode = el('select', { id: 'colour-mode', title: 'what the hoses are coloured by' });
  readonly grip = el('select', { id: 'grip', title: 'how the mouse hand holds the hose (hold F, A or B while grabbing to override)' });
  private readonly envelopeRow = el('div', { class: 'row', id: 'envelope-row' });
  readonly envelopeToggle = el('input', { id: 'envelope-toggle', type: 'checkbox' });
  private readonly envelopeName = el('span', { id: 'envelope-name', class: 'muted' });
  private readonly message = el('div', { id: 'message' });
  readonly plot: LoadPlot;
  private readonly pauseBtn = el('button', { id: 'pause' }, 'Pause');
  private readonly recordBtn = el('button', { id: 'record' }, 'Record');
  private readonly posture = el('select', { id: 'posture' });
  private readonly population = el('select', { id: 'population' });
  private readonly duty = el('select', { id: 'duty' });
  private readonly replayBar = el('div', { id: 'replay-bar' });
  readonly replaySlider = el('input', { id: 'replay-slider', type: 'range', min: '0', max: '1000', value: '0' });
  readonly replayPlay = el('button', { id: 'replay-play' }, 'Pause');
  /** Where the moving parts' sliders go (part_controls.ts). */
  readonly partsSlot = el('div', { id: 'parts' });
  /** Where the worker's reach, contacts and posture scores go (manikin.ts). */
  readonly workerSlot = el('div', { id: 'worker' });
  private readonly findings = el('div', { id: 'findings' });
  /** The findings listed, to skip rebuilding the list when they did not change. */
  private findingsShown = '';
  /** Where the author mode's controls go (author.ts). */
  readonly authorSlot = el('div', { id: 'author-slot' });
  private paused = false;
  private authorBtn: HTMLButtonElement | null = null;
  private recording = false;
  private profileShown = '';

  constructor(parent: HTMLElement, private readonly actions: PanelActions) {
    this.root = el('aside', { id: 'panel' });
    parent.appendChild(this.root);
    const title = el('h1', {}, 'Pliant');
    const controls = el('div', { class: 'row' });
    const stepBtn = el('button', { id: 'step' }, 'Step');
    const stepN = el('input', { id: 'step-n', type: 'number', min: '1', max: '100000', value: '1000', title: 'steps per click' });
    const resetBtn = el('button', { id: 'reset' }, 'Reset');
    const reportBtn = el('button', { id: 'report', title: 'write the session report (report.html, CSVs) on the server' }, 'Report');
    this.pauseBtn.onclick = () => {
      this.actions.pause(!this.paused);
    };
    stepBtn.onclick = () => this.actions.step(Math.max(1, Math.min(100000, Number(stepN.value) || 1)));
    resetBtn.onclick = () => this.actions.reset();
    reportBtn.onclick = () => this.actions.report();
    controls.append(this.pauseBtn, stepBtn, stepN, resetBtn, reportBtn);

    const ergo = el('div', { class: 'row' });
    const opts = (s: HTMLSelectElement, values: string[]) => {
      for (const v of values) s.append(el('option', { value: v }, v));
      s.onchange = () => this.actions.ergonomics(this.posture.value, this.population.value, this.duty.value);
    };
    opts(this.posture, ['standing', 'crouching', 'sitting']);
    opts(this.population, ['women', 'men']);
    opts(this.duty, ['occasional', 'continuous']);
    ergo.append(this.posture, this.population, this.duty);

    const files = el('div', { class: 'row' });
    const open = el('input', { id: 'open-scene', type: 'file', accept: '.toml,.json' });
    open.style.display = 'none';
    const openBtn = el('button', { id: 'open' }, 'Open scene…');
    openBtn.onclick = () => open.click();
    open.onchange = () => {
      const f = open.files?.[0];
      if (f !== undefined) this.actions.openScene(f);
      open.value = '';
    };
    this.recordBtn.onclick = () => this.actions.record(!this.recording);
    const replay = el('input', { id: 'replay-file', type: 'file', accept: '.json' });
    replay.style.display = 'none';
    const replayBtn = el('button', { id: 'replay' }, 'Replay…');
    replayBtn.onclick = () => replay.click();
    replay.onchange = () => {
      const f = replay.files?.[0];
      if (f !== undefined) this.actions.replayFile(f);
      replay.value = '';
    };
    const authorBtn = el('button', { id: 'author-mode', title: 'author a scene: hoses, stubs and clips by clicking on parts' }, 'Author');
    authorBtn.onclick = () => {
      authorBtn.blur();
      this.actions.author();
    };
    this.authorBtn = authorBtn;
    files.append(openBtn, open, this.recordBtn, replayBtn, replay, authorBtn);

    for (const m of COLOUR_MODES) this.colourMode.append(el('option', { value: m.id }, m.label));
    this.colourMode.onchange = () => this.actions.colourMode(this.colourMode.value as ColourMode);
    for (const g of GRIPS) this.grip.append(el('option', { value: g }, gripLabel(g)));
    this.grip.onchange = () => this.actions.grip(this.grip.value as Grip);
    const view = el('div', { class: 'row' });
    view.append(el('label', {}, 'Colour '), this.colourMode, el('label', {}, ' Grip '), this.grip);
    const envFile = el('input', { id: 'envelope-file', type: 'file', accept: '.glb,.gltf,.stl' });
    envFile.style.display = 'none';
    const envBtn = el('button', { id: 'envelope-open', title: 'a tolerance envelope from `pliant study` (envelope.glb or <hose>.stl); or drop it on the view' }, 'Envelope…');
    envBtn.onclick = () => envFile.click();
    envFile.onchange = () => {
      const f = envFile.files?.[0];
      if (f !== undefined) this.actions.envelopeFile(f);
      envFile.value = '';
    };
    this.envelopeToggle.onchange = () => this.actions.envelopeVisible(this.envelopeToggle.checked);
    const envClear = el('button', { id: 'envelope-clear' }, 'Clear');
    envClear.onclick = () => this.actions.envelopeClear();
    const envLabel = el('label', {}, ' show ');
    envLabel.prepend(this.envelopeToggle);
    this.envelopeRow.append(envLabel, this.envelopeName, envClear);
    this.envelopeRow.hidden = true;
    files.append(envBtn, envFile);

    const liveBtn = el('button', { id: 'live' }, 'Back to live');
    liveBtn.onclick = () => this.actions.live();
    this.replayBar.append(el('span', {}, 'Replay '), this.replayPlay, this.replaySlider, liveBtn);
    this.replayBar.hidden = true;

    const canvas = el('canvas', { id: 'plot', width: '300', height: '130' });
    this.plot = new LoadPlot(canvas);
    const help = el('p', { class: 'help' },
      'Drag a hose to pull it; Shift-drag or wheel: depth; Alt/Ctrl-drag: turn the hand; hold F, A or B while grabbing: firm, axial or ball grip. Drag elsewhere to orbit. Drop a .glb/.stl envelope on the view to show it.');
    this.root.append(
      title, this.status, this.scene, this.clock, controls,
      el('h2', {}, 'Ergonomics'), ergo,
      el('h2', {}, 'View'), view,
      el('h2', {}, 'Session'), files, this.envelopeRow, this.replayBar, this.authorSlot,
      el('h2', {}, 'Parts that move'), this.partsSlot,
      el('h2', {}, 'Hands'), this.hands, canvas,
      el('h2', {}, 'Worker'), this.workerSlot,
      el('h2', {}, 'Stubs and clips'), this.fasteners,
      el('h2', {}, 'Installation checks'), this.checks,
      el('h2', {}, 'Verdict so far'), this.verdict,
      el('h2', {}, 'Findings'), this.findings,
      this.message, help,
    );
  }

  setStatus(text: string): void {
    this.status.textContent = text;
  }

  setMessage(text: string, error = false): void {
    this.message.textContent = text;
    this.message.className = error ? 'error' : '';
  }

  setRecording(on: boolean, frames = 0): void {
    this.recording = on;
    this.recordBtn.textContent = on ? `Stop & save (${frames})` : 'Record';
    this.recordBtn.classList.toggle('on', on);
  }

  setAuthoring(on: boolean): void {
    this.authorBtn?.classList.toggle('on', on);
    if (this.authorBtn) this.authorBtn.textContent = on ? 'Leave author mode' : 'Author';
  }

  /** The envelopes shown (names), or none: the row with the show toggle. */
  setEnvelopes(names: string[], visible: boolean): void {
    this.envelopeRow.hidden = names.length === 0;
    this.envelopeName.textContent = names.join(', ');
    this.envelopeToggle.checked = visible;
  }

  setReplay(on: boolean): void {
    this.replayBar.hidden = !on;
  }

  welcome(w: Welcome): void {
    this.scene.textContent = `${w.session.scene} — ${w.session.hoses.length} hose(s), ${w.session.parts.length} part(s)`;
    this.scene.title = w.session.source;
    this.plot.clear();
    this.profileShown = '';
    this.findingsShown = '';
  }

  /** A snapshot drawn, and its verdict's findings (findings.ts). */
  snapshot(s: Snapshot, findings: readonly FindingRow[] = []): void {
    this.paused = s.paused;
    this.pauseBtn.textContent = s.paused ? 'Resume' : 'Pause';
    this.clock.textContent = `t = ${s.time.toFixed(2)} s · step ${s.step} · real-time factor ${s.real_time_factor.toFixed(2)}${s.paused ? ' · paused' : ''}`;
    if (s.notice !== undefined) this.setMessage(s.notice, true);
    if (s.ergonomics !== undefined) {
      const e = s.ergonomics;
      const key = `${e.push_posture}/${e.population}/${e.duty}`;
      if (key !== this.profileShown) {
        this.profileShown = key;
        this.posture.value = e.push_posture;
        this.population.value = e.population;
        this.duty.value = e.duty;
      }
    }
    // hands
    const rows: HTMLElement[] = [];
    for (const h of s.hands) {
      const f = norm(h.force);
      const t = norm(h.torque);
      const row = el('div', { class: 'hand', 'data-hand': String(h.hand_id) });
      row.append(
        el('div', { class: 'hand-title', 'data-grip': h.grip ?? 'firm' },
          `Hand ${h.hand_id} on hose ${h.hose} · ${h.grip ?? 'firm'} grip${h.kind ? ` — worst: ${h.kind}` : ''}`),
        el('div', { class: 'force', 'data-value': f.toFixed(3) },
          `Force ${fmt(f)} N (${h.force_kind ?? '–'}) / limit ${fmt(h.force_limit)} N`),
        bar(h.force_ratio),
        el('div', { class: 'torque', 'data-value': t.toFixed(4) },
          `Torque ${fmt(t, 2)} N·m; worst ${h.torque_kind ?? 'moment'} / limit ${fmt(h.torque_limit, 2)} N·m (guidance)`),
        bar(h.torque_ratio),
      );
      rows.push(row);
      this.plot.add(s.time, h.hand_id, h.force_ratio ?? 0, h.torque_ratio ?? 0);
    }
    if (rows.length === 0) rows.push(el('div', { class: 'muted' }, 'No hand holds a hose. Drag one.'));
    this.hands.replaceChildren(...rows);
    this.plot.draw(s.time);
    // fasteners
    const frows = s.fasteners.map((f) =>
      el('div', { class: `fastener${f.assembled ? ' ok' : ''}` },
        `${f.kind} '${f.name}': ${f.final_state}${f.assembled ? ' ✓' : ''} · now ${fmt(f.force)} N · peak ${fmt(f.max_force)} N`),
    );
    if (frows.length === 0) frows.push(el('div', { class: 'muted' }, 'none in this scene'));
    this.fasteners.replaceChildren(...frows);
    // installation checks (bend radius, twist): the worst violation per hose and check
    const crows = (s.checks ?? []).map((c) =>
      el('div', { class: 'check', 'data-check': c.check, 'data-hose': String(c.hose) },
        `hose '${c.hose_name}': ${violationText(c)} at s = ${(1e3 * c.arc_length).toFixed(0)} mm, ` +
        `t = ${c.time.toFixed(2)} s (violated ${c.first_time.toFixed(2)}–${c.last_time.toFixed(2)} s)`),
    );
    if (crows.length === 0) crows.push(el('div', { class: 'muted' }, 'no violation so far'));
    this.checks.replaceChildren(...crows);
    // verdict
    const v = s.verdict;
    if (v !== undefined) {
      const word = v.feasible === null ? 'nothing judged yet' : v.feasible ? 'feasible so far' : 'NOT feasible';
      const head = el('div', { class: `verdict-word ${v.feasible === null ? '' : v.feasible ? 'ok' : 'bad'}` }, word);
      const list = el('ul');
      for (const r of v.reasons) list.append(el('li', {}, r));
      for (const r of v.pending) list.append(el('li', { class: 'muted' }, r));
      // twist and bending at the hand: guidance only (dissertation 3.3.3)
      for (const r of v.warnings ?? []) list.append(el('li', { class: 'muted warning' }, `warning: ${r}`));
      this.verdict.replaceChildren(head, list);
    }
    this.showFindings(findings);
  }

  /** The findings, one row each: kind, whom it names, value against limit, time; a
   *  click highlights what it names (and seeks a replay to its time). */
  private showFindings(rows: readonly FindingRow[]): void {
    const key = JSON.stringify(rows);
    if (key === this.findingsShown) return;
    this.findingsShown = key;
    const items = rows.map((r, i) => {
      const item = el('li', { class: `finding ${r.list}`, 'data-kind': r.kind, 'data-index': String(i) });
      if (r.hose !== null) item.dataset.hose = String(r.hose);
      if (r.part !== null) item.dataset.part = String(r.part);
      if (r.time !== null) item.dataset.time = String(r.time);
      item.append(
        el('span', { class: 'finding-kind' }, r.kind.replace(/_/g, ' ')),
        el('span', {}, [r.subject, r.measure].filter((x) => x !== '').join(': ')),
        el('span', { class: 'muted' }, r.time === null ? '' : ` t = ${r.time.toFixed(2)} s`),
      );
      item.title = r.list === 'reasons' ? 'a reason of the verdict' : `${r.list}`;
      item.onclick = () => this.actions.finding(r);
      return item;
    });
    const list = el('ul');
    list.append(...items);
    this.findings.replaceChildren(items.length === 0 ? el('div', { class: 'muted' }, 'none') : list);
  }
}
