// A text sprite: a canvas to draw on, its texture (sRGB) and a sprite that always faces
// the eye and is drawn over the scene (no depth test). Force read-outs, violation labels
// and the controllers' grip labels are such sprites.

import * as THREE from 'three';

export interface CanvasSprite { sprite: THREE.Sprite; canvas: HTMLCanvasElement; texture: THREE.CanvasTexture }

/** A sprite showing a `width` × `height` pixel canvas, drawn in `renderOrder`. */
export function canvasSprite(width: number, height: number, renderOrder = 10): CanvasSprite {
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: texture, depthTest: false, transparent: true }));
  sprite.renderOrder = renderOrder;
  return { sprite, canvas, texture };
}
