// The Author mode's document and its undo (docs/authoring.md), apart from picking, drawing
// and the DOM (author.ts): the authored hoses, stubs and clips on top of the served scene
// file's own structure, written back as a scene document in the file's length unit; and
// the edit history. Pure: no DOM, no three.js (unit-tested in node).

import type { Json } from './toml';
import type { Vec3 } from './protocol';

export type Doc = { [key: string]: Json | undefined };

export type ClipType = 'fixed' | 'rotating' | 'sliding' | 'cable_tie';

/** All lengths in metres, world frame (converted to the file's unit when written). */
export interface AuthorHose {
  name: string;
  material: string;
  /** null: the library hose's own section. */
  section: { d_inner: number; d_outer: number } | null;
  points: Vec3[];
  /** Fix the first node (a leading `fix` action: the live session starts with it). */
  fixStart: boolean;
}
export interface AuthorStub { name: string; origin: Vec3; axis: Vec3; length: number; diameter: number; hose: string | null; end: 'start' | 'end' }
export interface AuthorClip {
  name: string; origin: Vec3; opening: Vec3; orientation: Vec3; type: ClipType;
  opening_width: number; inner_diameter: number; snap_force_n: number; hose: string | null;
}
export interface AuthorState { base: Doc; hoses: AuthorHose[]; stubs: AuthorStub[]; clips: AuthorClip[] }

const clone = <T>(x: T): T => JSON.parse(JSON.stringify(x)) as T;

/** Length in metres → the file's unit (`mm` or `m`), rounded to a micrometre. */
export function toFileUnit(x: number, unit: string): number {
  const f = unit === 'mm' ? 1000 : 1;
  const digits = unit === 'mm' ? 3 : 6;
  return Number((x * f).toFixed(digits)) + 0; // + 0: no -0 in the file
}

/** A direction, normalised and rounded to 6 digits. */
function direction(p: Vec3): number[] {
  const l = Math.hypot(p[0], p[1], p[2]) || 1;
  return p.map((x) => Number((x / l).toFixed(6)) + 0);
}

/**
 * The scene document: the base scene (never changed) with the authored hoses (a `line`
 * for two points, else a `spline` through the inner ones), stubs and clips appended, a
 * leading `fix` action for each hose whose start is fixed, lengths in `unit`.
 */
export function sceneDocument(s: AuthorState, name: string, unit: string): Doc {
  const u = (x: number) => toFileUnit(x, unit);
  const uv = (p: Vec3) => p.map(u);
  const doc = clone(s.base);
  doc.name = name;
  const arr = (k: string): Json[] => (Array.isArray(doc[k]) ? (doc[k] as Json[]) : []);
  const hoses = arr('hoses');
  const fixes: Json[] = [];
  for (const h of s.hoses) {
    if (h.points.length < 2) continue;
    const pts = h.points;
    const last = pts[pts.length - 1];
    const path = pts.length === 2
      ? [{ line: { to: uv(last) } }]
      : [{ spline: { through: pts.slice(1, -1).map(uv), to: uv(last) } }];
    const entry: Doc = { name: h.name, material: h.material };
    if (h.section !== null) entry.section = { d_inner: u(h.section.d_inner), d_outer: u(h.section.d_outer) };
    entry.start = uv(pts[0]);
    entry.path = path;
    hoses.push(entry);
    if (h.fixStart) fixes.push({ action: 'fix', hose: h.name, node: 0 });
  }
  doc.hoses = hoses;
  const stubs = arr('stubs');
  for (const st of s.stubs) {
    const e: Doc = { name: st.name, origin: uv(st.origin), axis: direction(st.axis), length: u(st.length), diameter: u(st.diameter) };
    if (st.hose !== null) { e.hose = st.hose; e.end = st.end; }
    stubs.push(e);
  }
  if (stubs.length > 0) doc.stubs = stubs;
  const clips = arr('clips');
  for (const c of s.clips) {
    const e: Doc = {
      name: c.name, origin: uv(c.origin), opening: direction(c.opening), orientation: direction(c.orientation),
      opening_width: u(c.opening_width), inner_diameter: u(c.inner_diameter),
    };
    if (c.type !== 'cable_tie') e.snap_force_n = c.snap_force_n;
    if (c.hose !== null) e.hose = c.hose;
    e.type = c.type;
    clips.push(e);
  }
  if (clips.length > 0) doc.clips = clips;
  const timeline = [...fixes, ...arr('timeline')];
  if (timeline.length > 0) doc.timeline = timeline;
  else delete doc.timeline;
  return doc;
}

/**
 * An undo/redo history of states kept as text (each a snapshot taken before an edit):
 * `record(before)` after an edit, `undo(now)` / `redo(now)` give the state to go back or
 * forward to (and keep `now` to return to). A new edit drops what could be redone; the
 * oldest steps beyond `limit` are forgotten.
 */
export class EditHistory {
  private past: string[] = [];
  private future: string[] = [];

  constructor(readonly limit = 200) {}

  /** An edit was made; `before` is the state it started from. */
  record(before: string): void {
    this.past.push(before);
    if (this.past.length > this.limit) this.past.shift();
    this.future = [];
  }

  /** The state before the last edit (null: nothing to undo); `now` can be redone. */
  undo(now: string): string | null {
    const prev = this.past.pop();
    if (prev === undefined) return null;
    this.future.push(now);
    return prev;
  }

  /** The state the last undo left (null: nothing to redo); `now` can be undone. */
  redo(now: string): string | null {
    const next = this.future.pop();
    if (next === undefined) return null;
    this.past.push(now);
    return next;
  }

  get canUndo(): boolean { return this.past.length > 0; }
  get canRedo(): boolean { return this.future.length > 0; }
  /** Nothing was edited yet (or every edit was forgotten). */
  get untouched(): boolean { return this.past.length === 0 && this.future.length === 0; }
}
