// Protections drawn over a hose tube (tape as a banded wrap, corrugated tube as a ribbed,
// darker, larger tube, sleeve as a matte sleeve), in the hose's colours shaded (the
// colour modes stay readable through them): one mesh per protection, its vertices
// rewritten in place from the hose tube's rings after every update (no allocation per
// frame). The shapes come from protection_geometry.ts.

import * as THREE from 'three';
import type { SurfaceMaterial } from './materials';
import { fillProtection, protectionStyle, ringRange, type ProtectionStyle } from './protection_geometry';
import type { ProtectionData } from './protocol';
import { dynamicTubeMesh } from './tube_mesh';

export class ProtectionMesh {
  readonly mesh: THREE.Mesh<THREE.BufferGeometry, SurfaceMaterial>;
  private readonly style: ProtectionStyle;
  private readonly pos: Float32Array;
  private readonly nrm: Float32Array;
  private readonly rgb: Float32Array;

  /** Over rings `first..last` of a tube with `radial + 1` vertices per ring. */
  private constructor(
    readonly data: ProtectionData,
    readonly first: number,
    readonly last: number,
    private readonly radial: number,
    hose: string,
  ) {
    this.style = protectionStyle(data.kind);
    const rings = last - first + 1;
    const per = radial + 1;
    this.pos = new Float32Array(rings * per * 3);
    this.nrm = new Float32Array(rings * per * 3);
    this.rgb = new Float32Array(rings * per * 3);
    this.mesh = dynamicTubeMesh(this.pos, this.nrm, this.rgb, rings, radial, this.style.roughness, 0);
    this.mesh.name = `protection:${hose}:${data.kind}`;
    this.mesh.frustumCulled = false;
    this.mesh.userData.protection = data.kind;
  }

  /** The cover of `data` over a tube of `rings` rings along a hose `length` long, if any. */
  static over(data: ProtectionData, length: number, rings: number, radial: number, hose: string): ProtectionMesh | null {
    const r = ringRange(data.from, data.to, length, rings);
    return r === null ? null : new ProtectionMesh(data, r[0], r[1], radial, hose);
  }

  /** Follows the hose tube's rings (`pos`, `nrm`, `rgb`: its vertices; `centre`: its
   *  ring centres). */
  update(pos: Float32Array, nrm: Float32Array, rgb: Float32Array, centre: Float32Array): void {
    fillProtection(pos, rgb, centre, this.radial, this.first, this.last, this.style, this.pos, this.rgb);
    const per = 3 * (this.radial + 1);
    this.nrm.set(nrm.subarray(this.first * per, (this.last + 1) * per));
    const g = this.mesh.geometry;
    g.attributes.position.needsUpdate = true;
    g.attributes.normal.needsUpdate = true;
    g.attributes.color.needsUpdate = true;
  }

  dispose(): void {
    this.mesh.geometry.dispose();
    this.mesh.material.dispose();
  }
}
