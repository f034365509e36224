// Recording and replay, in the client: a recording is the session's `welcome` and every
// snapshot received, each with its arrival time, saved as one JSON file
// ({"format":"pliant-recording","version":1,"welcome":…,"frames":[{"t":…,"snapshot":…}]}).
// A replay plays the snapshots back at their recorded pace through the same drawing code.

import type { Snapshot, Welcome } from './protocol';

export const RECORDING_FORMAT = 'pliant-recording';

export interface Recording {
  format: typeof RECORDING_FORMAT;
  version: 1;
  welcome: Welcome;
  frames: { t: number; snapshot: Snapshot }[];
}

/** Collects raw snapshot texts (no re-serialisation while recording). */
export class Recorder {
  private welcomeText = '';
  private frames: string[] = [];
  private start = 0;
  active = false;

  begin(welcomeRaw: string): void {
    this.welcomeText = welcomeRaw;
    this.frames = [];
    this.start = performance.now();
    this.active = true;
  }

  /** A new session (scene loaded) ends the recording of the old one. */
  get count(): number {
    return this.frames.length;
  }

  add(raw: string): void {
    if (!this.active) return;
    const t = (performance.now() - this.start) / 1000;
    this.frames.push(`{"t":${t.toFixed(4)},"snapshot":${raw}}`);
  }

  /** Stops and returns the recording as JSON text. */
  finish(): string {
    this.active = false;
    const text = `{"format":"${RECORDING_FORMAT}","version":1,"welcome":${this.welcomeText},"frames":[${this.frames.join(',')}]}`;
    this.frames = [];
    return text;
  }
}

/** Parses a recording, with a clear error for anything else. */
export function parseRecording(text: string): Recording {
  const r = JSON.parse(text) as Partial<Recording>;
  if (r.format !== RECORDING_FORMAT || r.version !== 1) throw new Error('not a Pliant recording (format "pliant-recording", version 1)');
  if (r.welcome?.type !== 'welcome' || !Array.isArray(r.frames)) throw new Error('recording without welcome or frames');
  return r as Recording;
}

/** Offers `text` as a file download. */
export function download(name: string, text: string): void {
  const url = URL.createObjectURL(new Blob([text], { type: 'application/json' }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

/** Plays a recording back: `frame(now)` gives the snapshot to show at wall time `now`. */
export class Player {
  private t0 = 0;
  private offset = 0; // recording time at t0
  playing = true;
  private index = 0;

  constructor(readonly recording: Recording) {
    this.t0 = performance.now();
  }

  get duration(): number {
    const f = this.recording.frames;
    return f.length === 0 ? 0 : f[f.length - 1].t;
  }

  /** Recording time now. */
  time(now: number): number {
    const t = this.playing ? this.offset + (now - this.t0) / 1000 : this.offset;
    return Math.min(t, this.duration);
  }

  setPlaying(on: boolean, now: number): void {
    this.offset = this.time(now);
    this.t0 = now;
    this.playing = on;
  }

  seek(fraction: number, now: number): void {
    this.offset = Math.max(0, Math.min(1, fraction)) * this.duration;
    this.t0 = now;
    this.index = 0;
  }

  /** Goes to the first frame whose snapshot is at simulated time `time` [s] or later
   *  (the last frame when none is). */
  seekSimulated(time: number, now: number): void {
    const f = this.recording.frames;
    if (f.length === 0) return;
    const k = frameAtSimulated(f, time);
    this.offset = f[k].t;
    this.t0 = now;
    this.index = 0;
  }

  /** The last frame at or before the current recording time. */
  frame(now: number): Snapshot | null {
    const f = this.recording.frames;
    if (f.length === 0) return null;
    const t = this.time(now);
    if (this.index >= f.length || f[this.index].t > t) this.index = 0;
    while (this.index + 1 < f.length && f[this.index + 1].t <= t) this.index++;
    return f[this.index].snapshot;
  }
}

/** The index of the first frame whose snapshot's simulated time is at least `time` [s]
 *  (the last frame when none is; 0 for no frames). A reset starts time again: the first
 *  such frame counts. */
export function frameAtSimulated(frames: readonly { snapshot: { time: number } }[], time: number): number {
  const k = frames.findIndex((f) => f.snapshot.time >= time);
  return k < 0 ? Math.max(0, frames.length - 1) : k;
}
