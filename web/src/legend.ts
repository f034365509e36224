// The colour legend over the view: the colour mode's quantity, a blue → green → red bar
// and the values at its ends and middle with their unit (colour_modes.ts). Redrawn only
// when the range changes.

import type { LegendRange } from './colour_modes';

export class Legend {
  readonly root = document.createElement('div');
  private readonly title = document.createElement('div');
  private readonly ticks = document.createElement('div');
  private shown = '';

  constructor(parent: HTMLElement) {
    this.root.id = 'legend';
    this.title.className = 'legend-title';
    const grad = document.createElement('div');
    grad.className = 'grad';
    this.ticks.className = 'legend-ticks';
    this.root.append(this.title, grad, this.ticks);
    parent.appendChild(this.root);
  }

  show(range: LegendRange): void {
    const key = `${range.title}|${range.ticks.join('|')}`;
    if (key === this.shown) return;
    this.shown = key;
    this.root.dataset.mode = range.mode;
    this.title.textContent = `${range.title} [${range.unit}]`;
    this.ticks.replaceChildren(
      ...range.ticks.map((t) => {
        const s = document.createElement('span');
        s.textContent = t;
        return s;
      }),
    );
  }
}
