// Shared by the end-to-end tests and the latency benchmark: starts `pliant serve --port 0`
// (binary from $PLIANT_BIN, default target/release/pliant), reads the URL it prints, and
// launches Debian's Chromium headless through playwright-core (never a downloaded browser).

import { spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { after, before } from 'node:test';
import { chromium } from 'playwright-core';

export const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
export const chromiumPath = process.env.PLIANT_CHROMIUM ?? '/usr/bin/chromium';

/**
 * The longest any single wait of the tests may take before it fails as hung (also every
 * page's default Playwright timeout). A hang guard, not a performance expectation: the
 * tests run on slow, shared, loaded machines with software WebGL, so every wait is for a
 * condition (a snapshot, a drawn frame, simulated time) and none sleeps and then asserts.
 */
export const HANG_GUARD_MS = 300_000;

/** Starts the server; resolves to { url, proc, stop() } once it printed its URL. */
export async function startServer(args = []) {
  const bin = path.resolve(repo, process.env.PLIANT_BIN ?? 'target/release/pliant');
  if (!existsSync(bin)) throw new Error(`no pliant binary at ${bin}: build it (cargo build --release -p pliant) or set PLIANT_BIN`);
  const proc = spawn(bin, ['serve', ...args, '--port', '0'], { cwd: repo, stdio: ['ignore', 'pipe', 'pipe'] });
  let out = '';
  const url = await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`pliant serve printed no URL within the hang guard:\n${out}`)), HANG_GUARD_MS);
    const onData = (d) => {
      out += d.toString();
      const m = out.match(/at (http:\/\/127\.0\.0\.1:\d+\/)/);
      if (m) {
        clearTimeout(timer);
        resolve(m[1]);
      }
    };
    proc.stdout.on('data', onData);
    proc.stderr.on('data', (d) => (out += d.toString()));
    proc.on('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`pliant serve exited with ${code}:\n${out}`));
    });
  });
  return {
    url,
    proc,
    output: () => out,
    stop: () =>
      new Promise((resolve) => {
        if (proc.exitCode !== null) return resolve();
        proc.once('exit', () => resolve());
        proc.kill('SIGINT');
        setTimeout(() => proc.kill('SIGKILL'), 3000).unref();
      }),
  };
}

/**
 * One `pliant serve` (with `args`) and one browser for the test file: started before its
 * tests, stopped after them. Returns { server, browser } filled in once started.
 */
export function sharedSession(args = []) {
  const shared = { server: null, browser: null };
  before(async () => {
    shared.server = await startServer(args);
    shared.browser = await launchBrowser();
  });
  after(async () => {
    await shared.browser?.close();
    await shared.server?.stop();
  });
  return shared;
}

export async function launchBrowser() {
  if (!existsSync(chromiumPath)) throw new Error(`no Chromium at ${chromiumPath}: run scripts/install-browser.sh`);
  return chromium.launch({
    executablePath: chromiumPath,
    args: [
      '--headless',
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
      '--enable-unsafe-swiftshader',
      '--use-angle=swiftshader',
      '--ignore-gpu-blocklist',
    ],
  });
}

/** Opens the viewer and waits until it has drawn a few frames of the live session. */
export async function openViewer(browser, url, { width = 1280, height = 800, query = '' } = {}) {
  const page = await browser.newPage({ viewport: { width, height } });
  page.setDefaultTimeout(HANG_GUARD_MS);
  const logs = [];
  page.on('console', (m) => logs.push(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => logs.push(`pageerror: ${e.message}`));
  await page.goto(url + query);
  try {
    await page.waitForFunction(() => window.pliant && window.pliant.shown !== null && window.pliant.frames > 5);
  } catch (e) {
    throw new Error(`viewer did not draw the session: ${e.message}\n${logs.join('\n')}`);
  }
  return { page, logs };
}

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/** Waits until the viewer has drawn `n` more frames (also in VR). */
export async function framesDrawn(page, n) {
  const f = await page.evaluate(() => window.pliant.frames);
  await page.waitForFunction(([f, n]) => window.pliant.frames >= f + n, [f, n]);
}

/** Waits until the snapshot shown is `dt` seconds of simulated time later than now. */
export async function simulated(page, dt) {
  const t = await page.evaluate(() => window.pliant.shown.time);
  await page.waitForFunction(([t, dt]) => window.pliant.shown.time >= t + dt, [t, dt]);
}

export function median(xs) {
  const s = [...xs].sort((a, b) => a - b);
  return s.length === 0 ? NaN : s[Math.floor((s.length - 1) / 2)];
}

export function percentile(xs, p) {
  const s = [...xs].sort((a, b) => a - b);
  return s.length === 0 ? NaN : s[Math.min(s.length - 1, Math.ceil((p / 100) * s.length) - 1)];
}

/** The distance between two points [x, y, z]. */
export const dist = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
