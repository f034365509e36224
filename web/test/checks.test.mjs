// End-to-end tests of the viewer's colour modes, violation markers, grips and tolerance
// envelopes: `pliant serve` (the real binary) on the engine bay demo,
// driven in headless Chromium. Every wait is for a condition (HANG_GUARD_MS only stops a
// hung test); nothing depends on the machine's speed.

import assert from 'node:assert/strict';
import { mkdirSync } from 'node:fs';
import path from 'node:path';
import { describe, test } from 'node:test';
import { framesDrawn, openViewer, repo, sharedSession } from './harness.mjs';

const LOW = { width: 1024, height: 640, query: '?quality=low' };
const shared = sharedSession();

/** Distance from `p` to the polyline through `nodes`. */
function toPolyline(p, nodes) {
  let best = Infinity;
  for (let i = 0; i + 1 < nodes.length; i++) {
    const a = nodes[i], b = nodes[i + 1];
    const ab = b.map((x, k) => x - a[k]);
    const ap = p.map((x, k) => x - a[k]);
    const l2 = ab.reduce((s, x) => s + x * x, 0) || 1;
    const t = Math.min(Math.max(ap.reduce((s, x, k) => s + x * ab[k], 0) / l2, 0), 1);
    best = Math.min(best, Math.hypot(...ap.map((x, k) => x - t * ab[k])));
  }
  return best;
}

/** A binary STL of a tetrahedron (metres) around `c`. */
function tetraStl(c, r) {
  const v = [[c[0] + r, c[1], c[2]], [c[0], c[1] + r, c[2]], [c[0], c[1], c[2] + r], [c[0] - r, c[1] - r, c[2] - r]];
  const faces = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]];
  const buf = Buffer.alloc(84 + 50 * faces.length);
  buf.writeUInt32LE(faces.length, 80);
  faces.forEach((f, i) => f.forEach((k, j) => v[k].forEach((x, d) => buf.writeFloatLE(x, 84 + 50 * i + 12 + 12 * j + 4 * d))));
  return buf;
}

/** A glTF binary with one triangle mesh named `name` (metres, z up as `pliant study` writes). */
function triangleGlb(name, c, r) {
  const pos = Buffer.alloc(36);
  [[c[0], c[1], c[2]], [c[0] + r, c[1], c[2]], [c[0], c[1] + r, c[2] + r]].forEach((p, i) => p.forEach((x, d) => pos.writeFloatLE(x, 12 * i + 4 * d)));
  const idx = Buffer.alloc(12);
  [0, 1, 2].forEach((k, i) => idx.writeUInt32LE(k, 4 * i));
  const bin = Buffer.concat([pos, idx]);
  const doc = {
    asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ name, mesh: 0 }],
    meshes: [{ name, primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [c[0], c[1], c[2]], max: [c[0] + r, c[1] + r, c[2] + r] },
      { bufferView: 1, componentType: 5125, count: 3, type: 'SCALAR' },
    ],
    bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: 36 }, { buffer: 0, byteOffset: 36, byteLength: 12 }],
    buffers: [{ byteLength: bin.length }],
  };
  let json = Buffer.from(JSON.stringify(doc));
  json = Buffer.concat([json, Buffer.alloc((4 - (json.length % 4)) % 4, 0x20)]);
  const head = Buffer.alloc(12);
  head.writeUInt32LE(0x46546c67, 0);
  head.writeUInt32LE(2, 4);
  head.writeUInt32LE(12 + 8 + json.length + 8 + bin.length, 8);
  const chunk = (b, type) => {
    const h = Buffer.alloc(8);
    h.writeUInt32LE(b.length, 0);
    h.writeUInt32LE(type, 4);
    return Buffer.concat([h, b]);
  };
  return Buffer.concat([head, chunk(json, 0x4e4f534a), chunk(bin, 0x004e4942)]);
}

describe('colour modes and checks', () => {
  test('the colour mode colours hoses along their length, the legend follows, markers sit at the violations', async () => {
    const { page } = await openViewer(shared.browser, shared.server.url, { width: 1280, height: 800 });
    try {
      // the demo's lower hose is delivered in a loop tighter than its minimum bend radius
      await page.waitForFunction(() => (window.pliant.shown?.checks ?? []).some((c) => c.check === 'bend_radius'));
      const snap = await page.evaluate(() => window.pliant.shown);
      const hose = snap.checks.find((c) => c.check === 'bend_radius').hose;
      const h = snap.hoses[hose];
      assert.equal(h.bend_radius_ratio.length, h.positions.length - 1, 'one value per beam');
      assert.equal(h.twist.length, h.positions.length - 1);
      assert.equal(h.axial_force.length, h.positions.length - 1);
      // hand load (the default): one colour along each hose
      assert.equal(await page.evaluate(() => window.pliant.colourMode), 'hand_load');
      const uniform = await page.evaluate((k) => window.pliant.tubeColours(k), hose);
      assert.equal(new Set(uniform.map((x) => x.toFixed(3))).size <= 3, true, 'one colour');
      assert.match(await page.textContent('#legend'), /hand load/);
      // bend radius: colours vary along the hose and reach red where the ratio is ≥ 1
      await page.selectOption('#colour-mode', 'bend_radius');
      await page.waitForFunction(() => document.querySelector('#legend').dataset.mode === 'bend_radius');
      assert.match(await page.textContent('#legend'), /minimum \/ current bend radius/);
      await page.waitForFunction((k) => {
        const s = window.pliant.shown;
        const worst = Math.max(...s.hoses[k].bend_radius_ratio);
        const c = window.pliant.tubeColours(k);
        let red = false;
        const seen = new Set();
        for (let i = 0; i < c.length; i += 3) {
          seen.add(`${c[i].toFixed(2)},${c[i + 1].toFixed(2)},${c[i + 2].toFixed(2)}`);
          if (c[i] > 0.9 && c[i + 1] < 0.1 && c[i + 2] < 0.1) red = true;
        }
        return seen.size > 3 && (worst < 1 || red);
      }, hose);
      // a marker per violation of the running checks, on its hose
      await page.waitForFunction(() => {
        const n = (window.pliant.shown.checks ?? []).filter((c) => c.check === 'bend_radius' || c.check === 'twist').length;
        return n > 0 && window.pliant.markers().length === n;
      });
      // markers and hoses read in one evaluation, so from one drawn frame (the session runs on)
      const markers = await page.evaluate(() => window.pliant.markers().map((m) => {
        const k = Number(m.key.split(':')[0]);
        return { ...m, hose: k, nodes: window.pliant.hoseNodes(k) };
      }));
      for (const m of markers) {
        assert.ok(toPolyline(m.position, m.nodes) < 1e-6, `marker ${m.key} at ${m.position} lies on hose ${m.hose}`);
      }
      // the panel lists the checks live; the running verdict names them
      assert.ok((await page.locator('#checks .check[data-check="bend_radius"]').count()) >= 1);
      assert.match(await page.textContent('#checks'), /bend radius \d+ mm < \d+ mm at s = \d+ mm/);
      assert.match(await page.textContent('#verdict'), /bend_radius check/);
      // the verdict's findings: a row per finding, naming the hose, the value against the
      // limit and the time; a click lights the hose up, a second click puts it out
      const row = page.locator(`#findings .finding[data-kind="check_violated"][data-hose="${hose}"]`).first();
      await row.scrollIntoViewIfNeeded();
      assert.match(await row.textContent(), /check violated.*hose '.+': bend radius \d+ mm < \d+ mm at s = \d+ mm.*t = \d+\.\d\d s/);
      await row.click();
      assert.deepEqual(await page.evaluate(() => window.pliant.highlighted()), { hoses: [hose], parts: [] });
      await page.locator(`#findings .finding[data-kind="check_violated"][data-hose="${hose}"]`).first().click();
      assert.deepEqual(await page.evaluate(() => window.pliant.highlighted()), { hoses: [], parts: [] });
      // twist and axial force: the legend's units
      await page.selectOption('#colour-mode', 'twist');
      await page.waitForFunction(() => /°\/m/.test(document.querySelector('#legend').textContent));
      await page.selectOption('#colour-mode', 'axial_force');
      await page.waitForFunction(() => /N \(tension\)/.test(document.querySelector('#legend').textContent));
      assert.ok((await page.evaluate(() => window.pliant.axialScale)) >= 1);
      // a picture for people (README, docs/colour-modes.png): bend radius colours and markers
      await page.selectOption('#colour-mode', 'bend_radius');
      await framesDrawn(page, 10);
      const dir = path.join(repo, 'target', 'e2e');
      mkdirSync(dir, { recursive: true });
      await page.screenshot({ path: path.join(dir, 'colour-modes.png') });
      await page.selectOption('#colour-mode', 'hand_load');
    } finally {
      await page.close();
    }
  });

  test('the grip chosen in the panel, or by a key held at the grab, reaches the server', async () => {
    const { page } = await openViewer(shared.browser, shared.server.url, LOW);
    try {
      const hose = (await page.evaluate(() => window.pliant.welcome.session.hoses.length)) - 1;
      const id = await page.evaluate(() => window.pliant.mouseHandId);
      const grabWith = async (key) => {
        if (key) await page.keyboard.down(key);
        // The hose may still swing from the last release, so the point read may have moved
        // on by the press: a press that picks nothing (lastPick null, or not renewed) is
        // let go and made again where the hose is drawn now.
        let at = null;
        for (let attempt = 0; at === null; attempt += 1) {
          assert.ok(attempt < 100, 'the hose could not be picked in 100 presses');
          const nodes = await page.evaluate((k) => window.pliant.hoseNodes(k), hose);
          const p = await page.evaluate(([n]) => window.pliant.screenOf(n), [nodes[nodes.length - 2]]);
          await page.mouse.move(p.x, p.y);
          await page.evaluate(() => { window.pickBefore = window.pliant.lastPick; });
          await page.mouse.down();
          const picked = await page.evaluate(() => {
            const pick = window.pliant.lastPick;
            return pick !== null && pick !== window.pickBefore;
          });
          if (picked) at = p;
          else await page.mouse.up();
        }
        await page.mouse.move(at.x + 5, at.y - 5);
        if (key) await page.keyboard.up(key);
        await page.waitForFunction((id) => (window.pliant.snapshot?.hands ?? []).some((h) => h.hand_id === id), id);
        const grip = await page.evaluate((id) => window.pliant.snapshot.hands.find((h) => h.hand_id === id).grip, id);
        const text = await page.textContent(`#hands .hand[data-hand="${id}"] .hand-title`);
        await page.mouse.up();
        await page.waitForFunction((id) => !(window.pliant.snapshot?.hands ?? []).some((h) => h.hand_id === id), id);
        return { grip, text };
      };
      await page.selectOption('#grip', 'axial');
      assert.equal(await page.evaluate(() => window.pliant.mouseGrip), 'axial');
      const panel = await grabWith(null);
      assert.equal(panel.grip, 'axial');
      assert.match(panel.text, /axial grip/);
      const key = await grabWith('b');
      assert.equal(key.grip, 'ball', 'B held at the grab: ball');
      await page.selectOption('#grip', 'firm');
      assert.equal((await grabWith(null)).grip, 'firm');
    } finally {
      await page.close();
    }
  });

  test('an envelope dropped on the view (STL) or opened (glTF) is shown, toggled and cleared', async () => {
    const { page, logs } = await openViewer(shared.browser, shared.server.url, LOW);
    try {
      const nodes = await page.evaluate(() => window.pliant.hoseNodes(0));
      const c = nodes[Math.floor(nodes.length / 2)];
      const stl = [...tetraStl(c, 0.05)];
      await page.evaluate((bytes) => {
        const dt = new DataTransfer();
        dt.items.add(new File([new Uint8Array(bytes)], 'lower.stl'));
        document.querySelector('#view').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
      }, stl);
      await page.waitForFunction(() => window.pliant.envelopes.loaded.length === 1).catch((e) => {
        throw new Error(`${e.message}\n${logs.join('\n')}`);
      });
      assert.deepEqual(await page.evaluate(() => window.pliant.envelopes.loaded), [{ name: 'lower.stl', meshes: 1 }]);
      assert.ok(await page.isVisible('#envelope-row'));
      assert.ok(await page.isChecked('#envelope-toggle'));
      await page.setInputFiles('#envelope-file', { name: 'envelope.glb', mimeType: 'model/gltf-binary', buffer: triangleGlb('upper', c, 0.05) });
      await page.waitForFunction(() => window.pliant.envelopes.loaded.length === 2);
      assert.match(await page.textContent('#envelope-name'), /lower\.stl, envelope\.glb/);
      await page.uncheck('#envelope-toggle');
      assert.equal(await page.evaluate(() => window.pliant.envelopes.visible), false);
      // not a mesh: a clear error, nothing added
      await page.setInputFiles('#envelope-file', { name: 'notes.txt', mimeType: 'text/plain', buffer: Buffer.from('hello') });
      await page.waitForFunction(() => /cannot show the envelope notes\.txt/.test(document.querySelector('#message').textContent));
      await page.click('#envelope-clear');
      assert.equal(await page.evaluate(() => window.pliant.envelopes.meshes), 0);
      assert.ok(!(await page.isVisible('#envelope-row')));
      assert.ok(!logs.some((l) => l.startsWith('pageerror')), logs.join('\n'));
    } finally {
      await page.close();
    }
  });

  test('?envelope=URL shows an envelope when the page opens', async () => {
    const glb = triangleGlb('lower', [0, 0, 0.3], 0.1).toString('base64');
    const query = `?quality=low&envelope=${encodeURIComponent(`data:model/gltf-binary;base64,${glb}`)}`;
    const { page } = await openViewer(shared.browser, shared.server.url, { ...LOW, query });
    try {
      await page.waitForFunction(() => window.pliant.envelopes.loaded.length === 1);
      assert.deepEqual(await page.evaluate(() => window.pliant.envelopes.loaded), [{ name: 'envelope (data URL)', meshes: 1 }]);
      assert.ok(await page.isVisible('#envelope-row'));
    } finally {
      await page.close();
    }
  });
});
