// Unit tests of the viewer's TOML writer (web/src/toml.ts), compiled by `npm run
// test:unit` into target/web-unit first. The round trip through the scene loader (the
// written file is accepted; a wrong field comes back as the loader's error) is in
// test/author.test.mjs and crates/server/tests/server.rs.

import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { toToml, tomlInline, tomlKey, tomlString } = await import(pathToFileURL(path.join(here, '..', '..', '..', 'target', 'web-unit', 'toml.js')).href);

test('a scene document is written in the format\'s layout', () => {
  const doc = {
    version: 1,
    hoses: [{ path: [{ spline: { through: [[0, 50, 327.5]], to: [420, 0, 360] } }], start: [-200, -50, 327.5], name: 'hose1', material: 'hose4' }],
    format: 'pliant-scene',
    length_unit: 'mm',
    name: 'bench route',
    simulation: { gravity: [0, 0, -9.81], time_step_safety: 0.5 },
    materials: { 'my rubber': { e_tension_mpa: 11.5, poisson: 0.49 } },
    parts: [{ box: { size: [600, 300, 40] }, name: 'bench', position: [0, 0, 300] }],
    timeline: [{ node: 0, hose: 'hose1', action: 'fix' }],
    checks: null,
  };
  assert.equal(toToml(doc, 'authored'), `# authored
format = "pliant-scene"
version = 1
name = "bench route"
length_unit = "mm"

[simulation]
gravity = [0, 0, -9.81]
time_step_safety = 0.5

[materials."my rubber"]
e_tension_mpa = 11.5
poisson = 0.49

[[hoses]]
name = "hose1"
material = "hose4"
path = [{ spline = { through = [[0, 50, 327.5]], to = [420, 0, 360] } }]
start = [-200, -50, 327.5]

[[parts]]
name = "bench"
box = { size = [600, 300, 40] }
position = [0, 0, 300]

[[timeline]]
action = "fix"
hose = "hose1"
node = 0
`);
});

test('values: strings escaped, numbers finite, nulls left out, long arrays one per line', () => {
  assert.equal(tomlString('a "b"\n\\'), '"a \\"b\\"\\n\\\\"');
  assert.equal(tomlKey('d_inner'), 'd_inner');
  assert.equal(tomlKey('a.b'), '"a.b"');
  assert.equal(tomlInline({ a: 1e-7, b: true, c: null, d: [] }), '{ a = 1e-7, b = true, d = [] }');
  assert.throws(() => tomlInline(Number.NaN), /finite/);
  assert.throws(() => tomlInline(Infinity), /finite/);
  const long = toToml({ xs: Array.from({ length: 20 }, (_, i) => [i, i, i]) });
  assert.match(long, /^xs = \[\n {2}\[0, 0, 0\],\n/);
  assert.equal(toToml({ hoses: [] }), 'hoses = []\n');
});
