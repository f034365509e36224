// Hoses as smooth swept tubes (SPEC I7): one tube surface per hose, swept along a
// Catmull-Rom curve through the nodes with the radius interpolated per node. The
// geometry's buffers are allocated once per session and rewritten in place for every
// snapshot (no allocation per frame). Each hose is coloured by its force colour value
// (SPEC I4), or along its length by per-node colour values (the colour modes of
// colour_modes.ts: bend radius, twist, axial force), through per-vertex colours.

import * as THREE from 'three';
import { colourRgb } from './colour';
import { HIGHLIGHT_GLOW, type SurfaceMaterial } from './materials';
import { ProtectionMesh } from './protections';
import { dynamicTubeMesh } from './tube_mesh';
import type { HoseData, Vec3 } from './protocol';

/** Curve samples per beam. */
const SUBDIV = 4;
/** Vertices around the tube. */
const RADIAL = 14;

export class HoseTube {
  readonly mesh: THREE.Mesh<THREE.BufferGeometry, SurfaceMaterial>;
  readonly nodes: number;
  private readonly rings: number;
  private readonly pos: Float32Array;
  private readonly nrm: Float32Array;
  private readonly rgb: Float32Array;
  private readonly scratch = new THREE.Color();
  // scratch (one ring's centre, tangent, normal, binormal, radius per ring)
  private readonly centre: Float32Array;
  private readonly tangent: Float32Array;
  private readonly ringRadius: Float32Array;
  /** Node positions of the last update (world frame). */
  readonly positions: Float64Array;
  colour = 0;
  /** The largest outer radius along the hose [m]. */
  readonly maxRadius: number;
  /** The protections drawn over it (children of `mesh`). */
  readonly covers: ProtectionMesh[] = [];

  constructor(readonly data: HoseData, readonly index: number) {
    this.nodes = data.radii.length;
    this.maxRadius = Math.max(0, ...data.radii);
    this.rings = (this.nodes - 1) * SUBDIV + 1;
    const nv = this.rings * (RADIAL + 1);
    this.pos = new Float32Array(nv * 3);
    this.nrm = new Float32Array(nv * 3);
    this.rgb = new Float32Array(nv * 3);
    this.centre = new Float32Array(this.rings * 3);
    this.tangent = new Float32Array(this.rings * 3);
    this.ringRadius = new Float32Array(this.rings);
    this.positions = new Float64Array(this.nodes * 3);
    this.mesh = dynamicTubeMesh(this.pos, this.nrm, this.rgb, this.rings, RADIAL, 0.55, 0.05);
    this.mesh.name = `hose:${data.name}`;
    this.mesh.castShadow = true;
    this.mesh.frustumCulled = false;
    this.mesh.userData.hose = index;
    for (const p of data.protections ?? []) {
      const cover = ProtectionMesh.over(p, data.length ?? 0, this.rings, RADIAL, data.name);
      if (cover === null) continue;
      this.covers.push(cover);
      this.mesh.add(cover.mesh);
    }
  }

  /** Lights the tube up (a finding clicked in the panel names this hose). */
  setHighlighted(on: boolean): void {
    this.mesh.material.emissive.setHex(on ? HIGHLIGHT_GLOW : 0x000000);
  }

  /** Node position i (world frame). */
  node(i: number): Vec3 {
    const p = this.positions;
    return [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
  }

  /**
   * Rewrites the tube through `nodes` [m] (world frame), coloured by `perNode` colour
   * values (one per node, interpolated along the tube) or, when null, all in colour
   * value `c`.
   */
  update(nodes: Vec3[], c: number, perNode: Float32Array | null = null): void {
    const n = Math.min(nodes.length, this.nodes);
    if (n < 2) return;
    for (let i = 0; i < n; i++) {
      this.positions[3 * i] = nodes[i][0];
      this.positions[3 * i + 1] = nodes[i][1];
      this.positions[3 * i + 2] = nodes[i][2];
    }
    this.sampleCurve();
    this.sweep();
    const g = this.mesh.geometry;
    g.attributes.position.needsUpdate = true;
    g.attributes.normal.needsUpdate = true;
    this.colour = c;
    this.paint(c, perNode);
    g.attributes.color.needsUpdate = true;
    for (const cover of this.covers) cover.update(this.pos, this.nrm, this.rgb, this.centre);
  }

  /** Vertex colours: ring by ring, the node values interpolated (or `c` throughout). */
  private paint(c: number, perNode: Float32Array | null): void {
    const N = this.nodes;
    for (let k = 0; k < this.rings; k++) {
      let v = c;
      if (perNode !== null && perNode.length >= N) {
        const i = Math.min(Math.floor(k / SUBDIV), N - 2);
        const t = (k - i * SUBDIV) / SUBDIV;
        v = perNode[i] + (perNode[i + 1] - perNode[i]) * t;
      }
      if (k > 0 && perNode === null) {
        this.rgb.copyWithin(k * (RADIAL + 1) * 3, 0, (RADIAL + 1) * 3);
        continue;
      }
      const [r, gg, b] = colourRgb(v);
      this.scratch.setRGB(r, gg, b, THREE.SRGBColorSpace); // to linear, as three.js draws
      for (let j = 0; j <= RADIAL; j++) {
        const o = 3 * (k * (RADIAL + 1) + j);
        this.rgb[o] = this.scratch.r;
        this.rgb[o + 1] = this.scratch.g;
        this.rgb[o + 2] = this.scratch.b;
      }
    }
  }

  /** Uniform Catmull-Rom through the nodes (end tangents mirrored): centres, tangents. */
  private sampleCurve(): void {
    const P = this.positions;
    const N = this.nodes;
    const radii = this.data.radii;
    let k = 0;
    for (let i = 0; i < N - 1; i++) {
      const i0 = Math.max(i - 1, 0);
      const i2 = i + 1;
      const i3 = Math.min(i + 2, N - 1);
      const last = i === N - 2 ? SUBDIV : SUBDIV - 1;
      for (let s = 0; s <= last; s++) {
        const t = s / SUBDIV;
        const t2 = t * t;
        const t3 = t2 * t;
        for (let d = 0; d < 3; d++) {
          const p0 = P[3 * i0 + d];
          const p1 = P[3 * i + d];
          const p2 = P[3 * i2 + d];
          const p3 = P[3 * i3 + d];
          // at the ends, mirror the missing neighbour so the end tangent follows the beam
          const q0 = i0 === i ? 2 * p1 - p2 : p0;
          const q3 = i3 === i2 ? 2 * p2 - p1 : p3;
          this.centre[3 * k + d] =
            0.5 * (2 * p1 + (-q0 + p2) * t + (2 * q0 - 5 * p1 + 4 * p2 - q3) * t2 + (-q0 + 3 * p1 - 3 * p2 + q3) * t3);
          this.tangent[3 * k + d] =
            0.5 * (-q0 + p2 + 2 * (2 * q0 - 5 * p1 + 4 * p2 - q3) * t + 3 * (-q0 + 3 * p1 - 3 * p2 + q3) * t2);
        }
        this.ringRadius[k] = radii[i] + (radii[i2] - radii[i]) * t;
        k++;
      }
    }
  }

  /** Sweeps the circle along the centres with parallel-transported frames. */
  private sweep(): void {
    const C = this.centre;
    const T = this.tangent;
    // first normal: any vector perpendicular to the first tangent
    let tx = T[0], ty = T[1], tz = T[2];
    let l = Math.hypot(tx, ty, tz) || 1;
    tx /= l; ty /= l; tz /= l;
    let nx: number, ny: number, nz: number;
    if (Math.abs(tz) < 0.9) { nx = -ty; ny = tx; nz = 0; } else { nx = 0; ny = -tz; nz = ty; }
    l = Math.hypot(nx, ny, nz) || 1;
    nx /= l; ny /= l; nz /= l;
    for (let k = 0; k < this.rings; k++) {
      let ux = T[3 * k], uy = T[3 * k + 1], uz = T[3 * k + 2];
      const ul = Math.hypot(ux, uy, uz);
      if (ul > 1e-12) { ux /= ul; uy /= ul; uz /= ul; } else { ux = tx; uy = ty; uz = tz; }
      // transport: remove the normal's component along the new tangent
      const dot = nx * ux + ny * uy + nz * uz;
      nx -= dot * ux; ny -= dot * uy; nz -= dot * uz;
      l = Math.hypot(nx, ny, nz);
      if (l < 1e-9) {
        if (Math.abs(uz) < 0.9) { nx = -uy; ny = ux; nz = 0; } else { nx = 0; ny = -uz; nz = uy; }
        l = Math.hypot(nx, ny, nz) || 1;
      }
      nx /= l; ny /= l; nz /= l;
      tx = ux; ty = uy; tz = uz;
      // binormal b = t × n
      const bx = ty * nz - tz * ny, by = tz * nx - tx * nz, bz = tx * ny - ty * nx;
      const r = this.ringRadius[k];
      const cx = C[3 * k], cy = C[3 * k + 1], cz = C[3 * k + 2];
      for (let j = 0; j <= RADIAL; j++) {
        const a = (j / RADIAL) * 2 * Math.PI;
        const ca = Math.cos(a), sa = Math.sin(a);
        const ox = ca * nx + sa * bx, oy = ca * ny + sa * by, oz = ca * nz + sa * bz;
        const v = 3 * (k * (RADIAL + 1) + j);
        this.pos[v] = cx + r * ox;
        this.pos[v + 1] = cy + r * oy;
        this.pos[v + 2] = cz + r * oz;
        this.nrm[v] = ox;
        this.nrm[v + 1] = oy;
        this.nrm[v + 2] = oz;
      }
    }
  }

  dispose(): void {
    this.mesh.geometry.dispose();
    this.mesh.material.dispose();
    for (const cover of this.covers) cover.dispose();
  }
}

/** The hose nearest to a ray: hose, beam, the point on the beam, and the ray parameter. */
export interface Pick {
  hose: number;
  beam: number;
  point: Vec3;
  distance: number;
  along: number;
}

/**
 * The beam (segment between two nodes) of any hose that passes closest to the ray
 * `origin + s·dir` (world frame, dir unit length), if within `slack` times its radius
 * plus `minSlack` metres. Nearest to the eye wins among hits.
 */
export function pickBeam(
  tubes: HoseTube[],
  origin: Vec3,
  dir: Vec3,
  slack = 1.5,
  minSlack = 0.004,
): Pick | null {
  let best: Pick | null = null;
  let bestScore = Infinity;
  for (const tube of tubes) {
    const P = tube.positions;
    for (let i = 0; i < tube.nodes - 1; i++) {
      const a: Vec3 = [P[3 * i], P[3 * i + 1], P[3 * i + 2]];
      const b: Vec3 = [P[3 * i + 3], P[3 * i + 4], P[3 * i + 5]];
      const r = raySegment(origin, dir, a, b);
      if (r === null) continue;
      const radius = Math.max(tube.data.radii[i], tube.data.radii[i + 1]);
      if (r.dist > radius * slack + minSlack) continue;
      // prefer the nearest along the ray, tie-broken by closeness to the axis
      const score = r.s + r.dist * 0.5;
      if (score < bestScore) {
        bestScore = score;
        best = { hose: tube.index, beam: i, point: r.point, distance: r.dist, along: r.s };
      }
    }
  }
  return best;
}

/** Closest approach of a ray and a segment: distance, ray parameter and segment point. */
function raySegment(o: Vec3, d: Vec3, a: Vec3, b: Vec3): { dist: number; s: number; point: Vec3 } | null {
  const u: Vec3 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
  const w: Vec3 = [o[0] - a[0], o[1] - a[1], o[2] - a[2]];
  const uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  const ud = u[0] * d[0] + u[1] * d[1] + u[2] * d[2];
  const uw = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
  const dw = d[0] * w[0] + d[1] * w[1] + d[2] * w[2];
  const den = uu - ud * ud; // |d| = 1
  let t = den > 1e-14 ? (uw - ud * dw) / den : 0; // segment parameter (× |u|² units)
  t = Math.min(Math.max(t, 0), 1);
  const p: Vec3 = [a[0] + t * u[0], a[1] + t * u[1], a[2] + t * u[2]];
  const s = (p[0] - o[0]) * d[0] + (p[1] - o[1]) * d[1] + (p[2] - o[2]) * d[2];
  if (s < 0) return null;
  const q: Vec3 = [o[0] + s * d[0], o[1] + s * d[1], o[2] + s * d[2]];
  const dist = Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
  return { dist, s, point: p };
}
