// A live plot (canvas 2D) of each hand's load against its limit over the last seconds:
// force and torque as a percentage of their limit values, with the limit (100 %) drawn in.

import { colourCss } from './colour';

interface Sample { t: number; hand: number; force: number; torque: number }

const HAND_COLOURS = ['#4fc3f7', '#ffb74d', '#ba68c8', '#81c784', '#f06292'];

export class LoadPlot {
  private samples: Sample[] = [];
  private readonly ctx: CanvasRenderingContext2D;

  constructor(readonly canvas: HTMLCanvasElement, readonly window_s = 10) {
    const ctx = canvas.getContext('2d');
    if (ctx === null) throw new Error('no 2D canvas');
    this.ctx = ctx;
  }

  /** Adds one snapshot's ratios (fractions of the limit) at simulated time `t`. */
  add(t: number, hand: number, force: number, torque: number): void {
    const last = this.samples[this.samples.length - 1];
    if (last !== undefined && t < last.t - 1e-9) this.samples = []; // reset or new scene
    this.samples.push({ t, hand, force, torque });
    const cut = t - this.window_s;
    let drop = 0;
    while (drop < this.samples.length && this.samples[drop].t < cut) drop++;
    if (drop > 256) this.samples.splice(0, drop);
  }

  clear(): void {
    this.samples = [];
  }

  draw(now: number): void {
    const { ctx, canvas } = this;
    const w = canvas.width;
    const h = canvas.height;
    ctx.clearRect(0, 0, w, h);
    ctx.fillStyle = '#161b22';
    ctx.fillRect(0, 0, w, h);
    const top = 1.5; // 150 % of the limit at the top
    const y = (r: number) => h - 14 - (Math.min(r, top) / top) * (h - 22);
    const x = (t: number) => 30 + ((t - (now - this.window_s)) / this.window_s) * (w - 36);
    // gradient band: blue → green → red up to the limit
    ctx.font = '10px sans-serif';
    ctx.fillStyle = '#8b949e';
    for (const r of [0, 0.5, 1]) {
      ctx.strokeStyle = r === 1 ? colourCss(1) : '#30363d';
      ctx.setLineDash(r === 1 ? [4, 3] : []);
      ctx.beginPath();
      ctx.moveTo(30, y(r));
      ctx.lineTo(w - 6, y(r));
      ctx.stroke();
      ctx.fillText(`${Math.round(r * 100)}%`, 2, y(r) + 3);
    }
    ctx.setLineDash([]);
    ctx.fillText(`last ${this.window_s} s`, w - 60, h - 2);
    const hands = [...new Set(this.samples.map((s) => s.hand))];
    hands.forEach((hand, k) => {
      const colour = HAND_COLOURS[k % HAND_COLOURS.length];
      for (const which of ['force', 'torque'] as const) {
        ctx.strokeStyle = colour;
        ctx.setLineDash(which === 'torque' ? [3, 3] : []);
        ctx.lineWidth = 1.5;
        ctx.beginPath();
        let first = true;
        let prevT = -Infinity;
        for (const s of this.samples) {
          if (s.hand !== hand || s.t < now - this.window_s) continue;
          const px = x(s.t);
          const py = y(s[which]);
          if (first || s.t - prevT > 1.0) ctx.moveTo(px, py);
          else ctx.lineTo(px, py);
          first = false;
          prevT = s.t;
        }
        ctx.stroke();
      }
    });
    ctx.setLineDash([]);
    ctx.lineWidth = 1;
  }
}

export function handColour(k: number): string {
  return HAND_COLOURS[k % HAND_COLOURS.length];
}
