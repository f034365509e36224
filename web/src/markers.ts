// Markers at the installation checks' violations: a red ring around the
// hose at each violation's arc length (its worst place since the last reset), with a
// label naming the check, the value and the limit. Markers are kept per hose and check
// and rebuilt only when the set of violations changes.

import * as THREE from 'three';
import { pointAtArcLength } from './arclength';
import { violationText } from './findings';
import type { CheckViolation, Vec3 } from './protocol';
import type { Stage } from './scene';
import { canvasSprite } from './sprite';

interface Marker { group: THREE.Group; sprite: THREE.Sprite; texture: THREE.CanvasTexture; text: string }

export class ViolationMarkers {
  private readonly markers = new Map<string, Marker>();
  private readonly ringGeometry = new THREE.TorusGeometry(1, 0.18, 8, 24);
  private readonly ringMaterial = new THREE.MeshBasicMaterial({ color: 0xff2020, depthTest: false, transparent: true, opacity: 0.9 });
  /** Markers under `stage.world` (the world frame, metres). */
  private readonly group = new THREE.Group();
  /** Labels placed so far per hose in this update (stacked so that they do not overlap). */
  private readonly stacked = new Map<number, number>();
  visible = true;

  constructor(private readonly stage: Stage) {
    this.group.name = 'violation-markers';
    stage.world.add(this.group);
  }

  /**
   * Markers at `checks` on the hoses drawn through the nodes `nodes(h)` (x, y, z
   * flattened, world frame) with largest radius `radius(h)` [m].
   */
  update(checks: readonly CheckViolation[], nodes: (h: number) => ArrayLike<number>, radius: (h: number) => number): void {
    this.group.visible = this.visible;
    const seen = new Set<string>();
    this.stacked.clear();
    for (const v of checks) {
      if (v.check !== 'bend_radius' && v.check !== 'twist') continue; // the running checks
      const key = `${v.hose}:${v.check}`;
      const along = nodes(v.hose);
      const p = pointAtArcLength(along, v.arc_length);
      if (p === null) continue;
      seen.add(key);
      let m = this.markers.get(key);
      if (m === undefined) {
        m = this.make();
        m.group.name = `violation:${key}`;
        this.markers.set(key, m);
      }
      this.label(m, violationText(v));
      // the ring around the hose: its axis along the hose's tangent there
      const a = pointAtArcLength(along, v.arc_length - 0.005) ?? p;
      const b = pointAtArcLength(along, v.arc_length + 0.005) ?? p;
      const t = new THREE.Vector3(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
      const r = 1.8 * radius(v.hose);
      m.group.position.set(p[0], p[1], p[2]);
      const ring = m.group.children[0];
      if (t.lengthSq() > 0) ring.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), t.normalize());
      ring.scale.setScalar(r);
      const w = Math.max(this.stage.radius * 0.35, 0.08);
      const stack = this.stacked.get(v.hose) ?? 0;
      this.stacked.set(v.hose, stack + 1);
      m.sprite.position.set(0, 0, 3 * r + 0.02 + stack * 0.3 * w);
      m.sprite.scale.set(w, w / 8, 1);
    }
    for (const [key, m] of this.markers) {
      if (seen.has(key)) continue;
      this.group.remove(m.group);
      m.texture.dispose();
      m.sprite.material.dispose();
      this.markers.delete(key);
    }
  }

  /** Positions of the markers now (world frame), for tests. */
  positions(): { key: string; position: Vec3 }[] {
    return [...this.markers].map(([key, m]) => ({ key, position: [m.group.position.x, m.group.position.y, m.group.position.z] }));
  }

  clear(): void {
    this.update([], () => [], () => 0);
  }

  private make(): Marker {
    const { sprite, texture } = canvasSprite(640, 80, 11);
    const ring = new THREE.Mesh(this.ringGeometry, this.ringMaterial);
    ring.renderOrder = 11;
    const group = new THREE.Group();
    group.add(ring, sprite);
    this.group.add(group);
    return { group, sprite, texture, text: '' };
  }

  private label(m: Marker, text: string): void {
    if (text === m.text) return;
    m.text = text;
    const ctx = (m.texture.image as HTMLCanvasElement).getContext('2d');
    if (ctx === null) return;
    ctx.clearRect(0, 0, 640, 80);
    ctx.fillStyle = 'rgba(60,0,0,0.85)';
    ctx.fillRect(0, 0, 640, 80);
    ctx.strokeStyle = '#ff2020';
    ctx.lineWidth = 6;
    ctx.strokeRect(3, 3, 634, 74);
    ctx.fillStyle = '#ffffff';
    ctx.font = 'bold 40px sans-serif';
    ctx.textBaseline = 'middle';
    ctx.fillText(text, 18, 42, 604);
    m.texture.needsUpdate = true;
  }
}
