// The verdict's findings (docs/protocol.md, "The verdict's findings") as rows the panel
// lists: what kind of line it is, whom it names (hose, part, hand, fastener, worker and
// body segment), the value against its limit, and when — plus the hose and part (indices
// into the welcome's lists) a click highlights and the time a replay seeks to. Pure: no
// DOM, no three.js (unit-tested in node).

import type { CheckViolation, LoadKind, VerdictFindings, VerdictLine } from './protocol';

/** Which of the verdict's lists a finding is in. */
export type FindingList = 'reasons' | 'pending' | 'warnings' | 'zones' | 'worker';

export interface FindingRow {
  list: FindingList;
  /** The finding's `kind` (docs/protocol.md's table). */
  kind: string;
  /** Whom it names, in words: "hose 'coolant'", "hand 0", "clip 'c1'", … (may be empty). */
  subject: string;
  /** The value against its limit, in words ("bend radius 31 mm < 45 mm"; may be empty). */
  measure: string;
  /** When [s] (null: no instant). */
  time: number | null;
  /** The hose and the part it names (indices into the welcome's lists; null: none). */
  hose: number | null;
  part: number | null;
}

/** A check's violation in words: "bend radius 31 mm < 45 mm", "twist 12.0 °/m > 10.0 °/m". */
export function violationText(v: Pick<CheckViolation, 'check' | 'value' | 'limit'>): string {
  switch (v.check) {
    case 'bend_radius':
      return `bend radius ${mm(v.value)} < ${mm(v.limit)}`;
    case 'twist':
      return `twist ${((v.value * 180) / Math.PI).toFixed(1)} °/m > ${((v.limit * 180) / Math.PI).toFixed(1)} °/m`;
    default:
      return `${v.check} ${v.value.toPrecision(3)} (limit ${v.limit.toPrecision(3)})`;
  }
}

const mm = (m: number) => `${(m * 1e3).toFixed(0)} mm`;
const num = (x: unknown): number | null => (typeof x === 'number' && Number.isFinite(x) ? x : null);
const str = (x: unknown): string => (typeof x === 'string' ? x : '');

/** A load's value with its unit: push and pull in N, twist and bending in N·m. */
function loadText(load: LoadKind, value: number): string {
  return load === 'push' || load === 'pull' ? `${value.toFixed(1)} N` : `${value.toFixed(2)} N·m`;
}

/**
 * The rows of a verdict's findings, list by list in the verdict's order (reasons,
 * pending, warnings, zones, worker). `hoses` and `parts` are the welcome's names: a
 * finding naming a hose or part by name or by index gets its index.
 */
export function findingRows(f: VerdictFindings, hoses: readonly string[], parts: readonly string[]): FindingRow[] {
  const hoseIndex = (h: unknown): number | null => {
    if (typeof h === 'number') return Number.isInteger(h) && h >= 0 && h < hoses.length ? h : null;
    const i = hoses.indexOf(str(h));
    return i < 0 ? null : i;
  };
  const partIndex = (p: unknown): number | null => {
    if (typeof p === 'number') return Number.isInteger(p) && p >= 0 && p < parts.length ? p : null;
    const i = parts.indexOf(str(p));
    return i < 0 ? null : i;
  };
  const out: FindingRow[] = [];
  const lists: [FindingList, VerdictLine[] | undefined][] = [
    ['reasons', f.reasons], ['pending', f.pending], ['warnings', f.warnings], ['zones', f.zones], ['worker', f.worker],
  ];
  for (const [list, lines] of lists) {
    for (const line of lines ?? []) out.push({ list, kind: line.kind, ...describe(line, hoseIndex, partIndex) });
  }
  return out;
}

type Described = Omit<FindingRow, 'list' | 'kind'>;

function describe(line: VerdictLine, hoseIndex: (h: unknown) => number | null, partIndex: (p: unknown) => number | null): Described {
  const none: Described = { subject: '', measure: '', time: null, hose: null, part: null };
  const working = (w: { fastener: string; name: string } | undefined) => (w === undefined ? '' : ` at ${w.fastener} '${w.name}'`);
  switch (line.kind) {
    case 'solver': {
      const l = line as Record<string, unknown>;
      const first = (l.first ?? {}) as Record<string, unknown>;
      const worst = (l.worst ?? {}) as Record<string, unknown>;
      if (line.doubt === 'rolled_back') {
        return { ...none, subject: `hose '${str(first.hose)}'`, measure: `${num(l.count) ?? 0} rollback(s): ${str(first.reason)}`, time: num(first.diverged_at), hose: hoseIndex(first.hose) };
      }
      if (line.doubt === 'out_of_balance') {
        const f = num(worst.residual_force);
        const lim = num(worst.force_limit);
        return { ...none, subject: 'solver', measure: f === null || lim === null ? '' : `residual ${f.toPrecision(3)} N > ${lim.toPrecision(3)} N`, time: num(worst.time) };
      }
      return { ...none, subject: 'solver', measure: `${num(l.steps) ?? 0} unstable step(s)` };
    }
    case 'stopped_early':
      return { ...none, measure: line.message };
    case 'hand_force_zone':
      return { ...none, subject: `hand ${line.hand}${working(line.working)}`, measure: `${line.zone.kind} ${loadText(line.zone.kind, line.zone.magnitude)}`, time: line.zone.time };
    case 'hand_load_over_limit':
      return { ...none, subject: `hand ${line.hand}${working(line.working)}`, measure: `${line.load} ${loadText(line.load, line.value)} > ${loadText(line.load, line.limit)} (×${line.ratio.toFixed(2)})`, time: line.time };
    case 'moment_above_guide':
      return { ...none, subject: `hand ${line.hand}`, measure: `${line.load} ${loadText(line.load, line.value)} > guide ${loadText(line.load, line.guide_hi)} (limit ${loadText(line.load, line.limit)})`, time: line.time };
    case 'fastener_not_fitted':
      return { ...none, subject: `${line.fastener} '${line.name}'`, measure: `ended ${line.final_state}` };
    case 'fastener_pending':
      return { ...none, subject: `${line.fastener} '${line.name}'`, measure: line.state };
    case 'check_violated': {
      const v = line.violation;
      return { ...none, subject: `hose '${v.hose_name}'${line.position ? ` ${line.position}` : ''}`, measure: `${violationText(v)} at s = ${mm(v.arc_length)}`, time: v.time, hose: hoseIndex(v.hose) };
    }
    case 'clearance_violated':
      return { subject: `hose '${line.hose}', part '${line.part}'`, measure: `gap ${mm(line.gap)} < ${mm(line.minimum)} ${line.position}`.trim(), time: line.time, hose: hoseIndex(line.hose), part: partIndex(line.part) };
    case 'worker': {
      const w = line.finding as Record<string, unknown>;
      if (w.kind === 'collision') {
        return { ...none, subject: `${str(w.who)}: segment '${str(w.segment)}' in part '${str(w.part)}'`, measure: `${mm(num(w.depth) ?? 0)} deep`, time: num(w.time), part: partIndex(w.part) };
      }
      return { ...none, subject: `${str(w.who)}: ${str(w.arm)} arm, hand ${num(w.hand) ?? '?'}`, measure: `out of reach by ${mm(num(w.distance) ?? 0)}`, time: num(w.time) };
    }
    case 'posture':
      return { ...none, subject: line.who, measure: `RULA ${String(line.rula.score)}, REBA ${String(line.reba.score)}`, time: line.rula.time };
    case 'not_posed':
      return { ...none, subject: line.who, measure: 'never posed' };
    case 'motion_extremes': {
      // the hose nearest its allowed bend radius names the line
      const worst = [...line.bend_radii].sort((a, b) => a.radius / a.allowed - b.radius / b.allowed)[0];
      const c = line.clearance;
      const parts = [worst === undefined ? '' : `hose '${worst.hose}' bend radius ${mm(worst.radius)} (allowed ${mm(worst.allowed)}) at ${worst.coordinate.toFixed(1)}`, c === undefined ? '' : `gap '${c.hose}'–'${c.part}' ${mm(c.gap)} at ${c.coordinate.toFixed(1)}`];
      return { ...none, subject: `part '${line.coordinate.part_name}' ${line.coordinate.kind} ${line.from.toFixed(1)} … ${line.to.toFixed(1)}`, measure: parts.filter((p) => p !== '').join('; '), hose: worst === undefined ? null : hoseIndex(worst.hose), part: partIndex(line.coordinate.part_name) };
    }
    case 'contact':
      return { ...none, subject: `part '${line.part}'`, measure: `from t = ${line.first_time.toFixed(2)} s to ${line.last_time.toFixed(2)} s`, time: line.first_time, part: partIndex(line.part) };
    case 'instability': {
      const l = line as Record<string, unknown>;
      if (line.note === 'snapped_through' || line.note === 'buckled') {
        return { ...none, subject: `hose '${str(l.hose)}', node ${num(l.node) ?? '?'}`, measure: line.note.replace('_', ' '), time: num(l.time), hose: hoseIndex(l.hose) };
      }
      if (line.note === 'explicit_fallback') return { ...none, subject: 'solver', measure: `${num(l.steps) ?? 0} step(s) taken explicitly`, time: num(l.first_time) };
      return { ...none, measure: `${num(l.count) ?? 0} more` };
    }
    case 'within_limits':
      return { ...none, measure: `${line.standard}: ${line.checks.join(', ')}` };
    case 'within_limits_so_far': {
      const w = line.worst;
      return w === undefined ? none : { ...none, subject: `hand ${w.hand}`, measure: `worst ${w.load} ${loadText(w.load, w.value)} of ${loadText(w.load, w.limit)} (×${w.ratio.toFixed(2)})`, time: w.time };
    }
    case 'checks_passed':
    case 'no_hand_acted':
      return { ...none, measure: line.stage };
  }
}
