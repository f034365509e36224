// A tube mesh whose vertices are rewritten in place every snapshot: the hose tubes and the
// protections over them share it.

import * as THREE from 'three';
import { surface, type SurfaceMaterial } from './materials';
import { tubeIndices } from './protection_geometry';

/**
 * A mesh over `rings` rings of `radial + 1` vertices whose positions, normals and
 * vertex colours are the arrays `pos`, `nrm`, `rgb` (rewritten by the caller, who then
 * flags the attributes `needsUpdate`).
 */
export function dynamicTubeMesh(
  pos: Float32Array,
  nrm: Float32Array,
  rgb: Float32Array,
  rings: number,
  radial: number,
  roughness: number,
  metalness: number,
): THREE.Mesh<THREE.BufferGeometry, SurfaceMaterial> {
  const g = new THREE.BufferGeometry();
  for (const [name, array] of [['position', pos], ['normal', nrm], ['color', rgb]] as const) {
    const a = new THREE.BufferAttribute(array, 3);
    a.setUsage(THREE.DynamicDrawUsage);
    g.setAttribute(name, a);
  }
  g.setIndex(tubeIndices(rings, radial));
  const m = surface({ color: 0xffffff, roughness, metalness });
  m.vertexColors = true;
  return new THREE.Mesh(g, m);
}
