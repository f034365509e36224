// Tolerance envelopes (SPEC T2): the swept volume of a hose over a study's runs,
// as `pliant study` writes it (`envelope/envelope.glb`, `envelope/<hose>.stl`: metres, z up,
// the scene's own coordinates — docs/study.md), shown as a translucent mesh in the
// session's world frame. Loaded by dropping the file on the view or by `?envelope=URL`;
// three.js' own GLTFLoader and STLLoader read the files.

import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import { disposeTree, type Stage } from './scene';

/** Larger files are refused before they are read (a voxel envelope is a few MB). */
const MAX_BYTES = 256 * 1024 * 1024;

export class Envelopes {
  /** The envelopes, in the world frame (under `stage.world`). */
  readonly group = new THREE.Group();
  private readonly material = new THREE.MeshLambertMaterial({
    color: 0x5fd0ff,
    transparent: true,
    opacity: 0.28,
    side: THREE.DoubleSide,
    depthWrite: false,
  });
  /** Names of the files shown and their mesh counts. */
  readonly loaded: { name: string; meshes: number }[] = [];

  constructor(stage: Stage) {
    this.group.name = 'envelopes';
    this.group.renderOrder = 5;
    stage.world.add(this.group);
  }

  get visible(): boolean {
    return this.group.visible;
  }

  set visible(on: boolean) {
    this.group.visible = on;
  }

  /** Reads a glTF binary (.glb), glTF JSON with embedded buffers (.gltf) or STL. */
  async load(data: ArrayBuffer, name: string): Promise<number> {
    if (data.byteLength > MAX_BYTES) throw new Error(`${name}: ${data.byteLength} bytes, more than the ${MAX_BYTES >> 20} MiB allowed`);
    const lower = name.toLowerCase();
    const head = new Uint8Array(data, 0, Math.min(4, data.byteLength));
    const glb = head.length === 4 && String.fromCharCode(...head) === 'glTF';
    let root: THREE.Object3D;
    if (lower.endsWith('.stl') && !glb) {
      root = new THREE.Mesh(new STLLoader().parse(data));
    } else if (glb || lower.endsWith('.glb') || lower.endsWith('.gltf')) {
      const gltf = await new GLTFLoader().parseAsync(data, '');
      root = gltf.scene;
    } else {
      throw new Error(`${name}: not a .glb, .gltf or .stl file`);
    }
    let meshes = 0;
    root.traverse((o) => {
      const m = o as THREE.Mesh;
      if (!m.isMesh) return;
      meshes++;
      const old = m.material;
      if (Array.isArray(old)) old.forEach((x) => x.dispose());
      else old?.dispose();
      m.material = this.material;
      if (m.geometry.getAttribute('normal') === undefined) m.geometry.computeVertexNormals();
      m.renderOrder = 5;
      m.name = `envelope:${m.name || name}`;
    });
    if (meshes === 0) {
      disposeTree(root);
      throw new Error(`${name}: no mesh in the file`);
    }
    this.group.add(root);
    this.group.visible = true;
    this.loaded.push({ name, meshes });
    return meshes;
  }

  /** Fetches `url` and loads it. */
  async loadUrl(url: string): Promise<number> {
    const res = await fetch(url);
    if (!res.ok) throw new Error(`${url}: HTTP ${res.status}`);
    const u = new URL(url, location.href);
    const name = u.protocol === 'data:' ? 'envelope (data URL)' : u.pathname.split('/').pop() || u.href;
    return this.load(await res.arrayBuffer(), name);
  }

  /** Removes every envelope. */
  clear(): void {
    for (const c of [...this.group.children]) {
      this.group.remove(c);
      c.traverse((o) => {
        const m = o as THREE.Mesh;
        if (m.isMesh) m.geometry.dispose();
      });
    }
    this.loaded.length = 0;
  }

  /**
   * Dropping .glb/.gltf/.stl files on `target` loads them; `done` gets a message (and
   * whether it is an error).
   */
  acceptDrops(target: HTMLElement, done: (message: string, error: boolean) => void): void {
    target.addEventListener('dragover', (e) => {
      e.preventDefault();
      if (e.dataTransfer) e.dataTransfer.dropEffect = 'copy';
    });
    target.addEventListener('drop', (e) => {
      e.preventDefault();
      for (const file of Array.from(e.dataTransfer?.files ?? [])) {
        void file
          .arrayBuffer()
          .then((buf) => this.load(buf, file.name))
          .then((n) => done(`envelope ${file.name}: ${n} mesh(es) shown`, false))
          .catch((err: Error) => done(`cannot show ${file.name}: ${err.message}`, true));
      }
    });
  }
}
