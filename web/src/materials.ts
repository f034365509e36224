// Surface materials: physically based in high quality, Lambert (much cheaper per pixel,
// which matters for software rendering) in low quality.

import * as THREE from 'three';

export type Quality = 'high' | 'low';
export type SurfaceMaterial = THREE.MeshStandardMaterial | THREE.MeshLambertMaterial;

let quality: Quality = 'high';

export function setQuality(q: Quality): void {
  quality = q;
}

export function surface(p: { color: number; roughness?: number; metalness?: number; side?: THREE.Side }): SurfaceMaterial {
  if (quality === 'low') return new THREE.MeshLambertMaterial({ color: p.color, side: p.side ?? THREE.FrontSide });
  return new THREE.MeshStandardMaterial({
    color: p.color,
    roughness: p.roughness ?? 0.6,
    metalness: p.metalness ?? 0,
    side: p.side ?? THREE.FrontSide,
  });
}

/** The glow of a highlighted hose or part (emissive colour). */
export const HIGHLIGHT_GLOW = 0x5a4a00;
