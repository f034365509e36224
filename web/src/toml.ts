// A small TOML writer for scene documents (docs/scene-format.md): a JSON value of the
// scene file's raw structure → TOML text that the scene loader reads back to the same
// value. Top-level objects become `[table]`s (an object of objects, such as `materials`,
// becomes `[materials.NAME]` tables), top-level arrays of objects `[[array]]`s, and
// everything deeper is written inline (`{ … }`, `[ … ]`), as the examples are written.
// Null and undefined values are left out (the format wants optional fields omitted).

export type Json = null | boolean | number | string | Json[] | { [key: string]: Json | undefined };

const isObject = (v: unknown): v is { [key: string]: Json | undefined } =>
  typeof v === 'object' && v !== null && !Array.isArray(v);

/** A key: bare when it can be, else a quoted string. */
export function tomlKey(k: string): string {
  return /^[A-Za-z0-9_-]+$/.test(k) ? k : tomlString(k);
}

/** A basic string: JSON's escapes are TOML's (TOML has no `\/`, JSON never writes it). */
export function tomlString(s: string): string {
  return JSON.stringify(s).replace(/[\u007f]/g, (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
}

export function tomlNumber(x: number): string {
  if (!Number.isFinite(x)) throw new Error(`cannot write ${x} in a scene file: numbers must be finite`);
  if (Number.isInteger(x) && Math.abs(x) < 1e15) return String(x);
  return String(x); // JS writes 0.5, 1e-7, 1.5e+21: each a TOML float
}

/** Any value inline. */
export function tomlInline(v: Json): string {
  if (v === null) throw new Error('null cannot be written in TOML');
  if (typeof v === 'boolean') return v ? 'true' : 'false';
  if (typeof v === 'number') return tomlNumber(v);
  if (typeof v === 'string') return tomlString(v);
  if (Array.isArray(v)) return `[${v.filter((x) => x !== null).map(tomlInline).join(', ')}]`;
  const parts = Object.entries(v)
    .filter(([, x]) => x !== null && x !== undefined)
    .map(([k, x]) => `${tomlKey(k)} = ${tomlInline(x as Json)}`);
  return parts.length === 0 ? '{}' : `{ ${parts.join(', ')} }`;
}

const isTableArray = (v: unknown): v is { [key: string]: Json | undefined }[] =>
  Array.isArray(v) && v.length > 0 && v.every(isObject);

/** Keys in the order of the scene format's documentation (the server's document comes
 *  with its keys sorted): those listed first, in this order, then the rest as they come. */
const FIRST = ['format', 'version', 'name', 'length_unit', 'action', 'hose', 'hand', 'node', 'material', 'section'];
const TABLE_ORDER = ['simulation', 'output', 'materials', 'ergonomics', 'checks', 'hoses', 'parts', 'stubs', 'clips', 'timeline'];

function ordered<T>(obj: { [key: string]: T }, first: string[]): [string, T][] {
  const rank = (k: string) => {
    const i = first.indexOf(k);
    return i < 0 ? first.length : i;
  };
  return Object.entries(obj)
    .map((e, i) => [e, i] as const)
    .sort((a, b) => rank(a[0][0]) - rank(b[0][0]) || a[1] - b[1])
    .map(([e]) => e);
}

/** `key = value` lines of a table's plain entries (arrays written one element a line
 *  when long). */
function entries(obj: { [key: string]: Json | undefined }): string {
  let out = '';
  for (const [k, v] of ordered(obj, FIRST)) {
    if (v === null || v === undefined) continue;
    let text = tomlInline(v);
    if (Array.isArray(v) && text.length > 90) {
      text = `[\n${v.filter((x) => x !== null).map((x) => `  ${tomlInline(x)},`).join('\n')}\n]`;
    }
    out += `${tomlKey(k)} = ${text}\n`;
  }
  return out;
}

/** The whole document as TOML. `comment` (lines) goes on top. */
export function toToml(doc: { [key: string]: Json | undefined }, comment = ''): string {
  let out = comment === '' ? '' : comment.split('\n').map((l) => `# ${l}`.trimEnd()).join('\n') + '\n';
  const plain: { [key: string]: Json | undefined } = {};
  const tables: [string, { [key: string]: Json | undefined }][] = [];
  const arrays: [string, { [key: string]: Json | undefined }[]][] = [];
  for (const [k, v] of ordered(doc, [...FIRST, ...TABLE_ORDER])) {
    if (v === null || v === undefined) continue;
    if (isObject(v)) tables.push([k, v]);
    else if (isTableArray(v)) arrays.push([k, v]);
    else plain[k] = v;
  }
  out += entries(plain);
  for (const [k, t] of tables) {
    const values = Object.values(t).filter((x) => x !== null && x !== undefined);
    if (values.length > 0 && values.every(isObject)) {
      // an object of objects (materials): one [k.NAME] table each
      for (const [name, sub] of Object.entries(t)) {
        if (!isObject(sub)) continue;
        out += `\n[${tomlKey(k)}.${tomlKey(name)}]\n${entries(sub)}`;
      }
    } else if (values.length > 0) {
      out += `\n[${tomlKey(k)}]\n${entries(t)}`;
    }
  }
  for (const [k, list] of arrays) {
    for (const item of list) out += `\n[[${tomlKey(k)}]]\n${entries(item)}`;
  }
  return out;
}
