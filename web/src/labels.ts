// Floating force read-outs: a text sprite above each hand showing its force and torque
// as a share of the limit, in the force colour. Canvases are redrawn only when the text
// changes.

import * as THREE from 'three';
import { colourCss } from './colour';
import { norm, type HandSnapshot } from './protocol';
import { canvasSprite } from './sprite';
import type { Stage } from './scene';

interface Label { sprite: THREE.Sprite; canvas: HTMLCanvasElement; texture: THREE.CanvasTexture; text: string }

export class ForceLabels {
  private labels = new Map<number, Label>();
  private readonly group = new THREE.Group();
  /** Label width in metres (in VR: readable at arm's length). */
  width = 0.16;

  constructor(private readonly stage: Stage) {
    stage.scene.add(this.group);
  }

  private make(): Label {
    const l = canvasSprite(512, 128);
    this.group.add(l.sprite);
    return { ...l, text: '' };
  }

  update(hands: HandSnapshot[]): void {
    const seen = new Set<number>();
    for (const h of hands) {
      seen.add(h.hand_id);
      let l = this.labels.get(h.hand_id);
      if (l === undefined) {
        l = this.make();
        this.labels.set(h.hand_id, l);
      }
      const text = `${norm(h.force).toFixed(1)} N  ${Math.round(100 * (h.force_ratio ?? h.ratio ?? 0))}%|${norm(h.torque).toFixed(2)} N·m  ${Math.round(100 * (h.torque_ratio ?? 0))}%`;
      if (text !== l.text) {
        l.text = text;
        const ctx = l.canvas.getContext('2d');
        if (ctx !== null) {
          const [a, b] = text.split('|');
          ctx.clearRect(0, 0, 512, 128);
          ctx.fillStyle = 'rgba(13,17,23,0.8)';
          ctx.beginPath();
          ctx.roundRect(4, 4, 504, 120, 18);
          ctx.fill();
          ctx.lineWidth = 8;
          ctx.strokeStyle = colourCss(h.colour);
          ctx.stroke();
          ctx.fillStyle = '#ffffff';
          ctx.font = 'bold 44px sans-serif';
          ctx.fillText(a, 24, 56);
          ctx.font = '36px sans-serif';
          ctx.fillStyle = '#c9d1d9';
          ctx.fillText(b, 24, 104);
        }
        l.texture.needsUpdate = true;
      }
      const width = this.stage.renderer.xr.isPresenting ? this.width : Math.max(this.stage.radius * 0.3, 0.05);
      const p = this.stage.toThree(h.position);
      p.y += width * 0.35;
      l.sprite.position.copy(p);
      l.sprite.scale.set(width, width / 4, 1);
    }
    for (const [id, l] of this.labels) {
      if (!seen.has(id)) {
        this.group.remove(l.sprite);
        l.texture.dispose();
        l.sprite.material.dispose();
        this.labels.delete(id);
      }
    }
  }
}
