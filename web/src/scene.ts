// The 3D stage: renderer, camera with orbit controls, lights, ground, and the rigid parts,
// stubs and clips of a session. Pliant's world is z-up; everything simulated hangs under
// `world`, a group turned so that z points up the screen (three.js is y-up). Converting
// between three.js space and Pliant's world frame always goes through `world`.

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { TransformControls } from 'three/examples/jsm/controls/TransformControls.js';
import { HIGHLIGHT_GLOW, setQuality, surface, type Quality, type SurfaceMaterial } from './materials';
import { carry } from './part_joints';
import type { FastenerData, PartPose, SceneData, Vec3 } from './protocol';

const PART_COLOURS = [0xb8b4ac, 0x9aa3ab, 0xc4b59a, 0xa9a9a9, 0xb0a8a0];

export class Stage {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  /** Pliant's world frame (z-up) inside three.js space (y-up). */
  readonly world = new THREE.Group();
  /** Parts, stubs, clips and ground of the current session. */
  private content = new THREE.Group();
  private ground: THREE.Object3D | null = null;
  /** The stubs, connectors and clips drawn, in the welcome's order, with their origin and
   *  turn where the scene placed them. */
  private fastenerObjects: { object: THREE.Object3D; origin: Vec3; rest: THREE.Quaternion }[] = [];
  /** Per fastener, the index of the part it sits on (-1: none): it is drawn at that
   *  part's pose. */
  private carriers: number[] = [];
  /** Centre and radius of the current session's scene, in the world frame. */
  centre = new THREE.Vector3();
  private readonly sun = new THREE.DirectionalLight(0xffffff, 2.2);
  radius = 1;

  /**
   * `low` quality (URL `?quality=low`): no antialiasing, no shadows, one pixel per CSS
   * pixel — for software rendering (headless tests, old machines).
   */
  constructor(readonly container: HTMLElement, readonly quality: Quality = 'high') {
    setQuality(quality);
    const low = quality === 'low';
    this.renderer = new THREE.WebGLRenderer({ antialias: !low, preserveDrawingBuffer: true, alpha: true });
    this.renderer.setPixelRatio(low ? 1 : Math.min(window.devicePixelRatio, 2));
    this.renderer.setSize(container.clientWidth, container.clientHeight);
    this.renderer.outputColorSpace = THREE.SRGBColorSpace;
    this.renderer.shadowMap.enabled = !low;
    this.renderer.shadowMap.type = THREE.PCFShadowMap;
    container.appendChild(this.renderer.domElement);

    this.scene.background = new THREE.Color(0x20262e);
    this.scene.fog = new THREE.Fog(0x20262e, 6, 14);
    this.camera = new THREE.PerspectiveCamera(45, container.clientWidth / container.clientHeight, 0.01, 100);
    this.camera.position.set(1.2, 1.0, 1.4);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = false;

    this.world.rotation.x = -Math.PI / 2; // Pliant z-up → three.js y-up
    this.world.add(this.content);
    this.scene.add(this.world);

    const hemi = new THREE.HemisphereLight(0xe8f0ff, 0x404040, 1.4);
    this.scene.add(hemi);
    const sun = this.sun;
    sun.position.set(2, 4, 3);
    sun.castShadow = true;
    sun.shadow.mapSize.set(1024, 1024);
    sun.shadow.camera.near = 0.5;
    sun.shadow.camera.far = 12;
    sun.shadow.bias = -0.0004;
    sun.shadow.normalBias = 0.004;
    const s = sun.shadow.camera as THREE.OrthographicCamera;
    s.left = s.bottom = -1.5;
    s.right = s.top = 1.5;
    this.scene.add(sun);
    this.scene.add(sun.target);
    const fill = new THREE.DirectionalLight(0xffffff, 0.6);
    fill.position.set(-3, 2, -2);
    this.scene.add(fill);

    new ResizeObserver(() => this.resize()).observe(container);
  }

  resize(): void {
    const w = this.container.clientWidth;
    const h = this.container.clientHeight;
    if (w === 0 || h === 0) return;
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.renderer.setSize(w, h);
  }

  /** World frame (Pliant, z-up) → three.js space. */
  toThree(p: Vec3, out = new THREE.Vector3()): THREE.Vector3 {
    return this.world.localToWorld(out.set(p[0], p[1], p[2]));
  }

  /** three.js space → world frame. */
  toWorld(v: THREE.Vector3): Vec3 {
    const l = this.world.worldToLocal(v.clone());
    return [l.x, l.y, l.z];
  }

  /**
   * A rotation given in three.js space, expressed in the world frame (W⁻¹·q·W), as
   * [x, y, z, w]. Hands start with the identity at the grab, so turns are sent as the
   * rotation since the grab.
   */
  toWorldRotation(q: THREE.Quaternion): [number, number, number, number] {
    const w = new THREE.Quaternion();
    this.world.getWorldQuaternion(w);
    const l = w.clone().invert().multiply(q).multiply(w);
    return [l.x, l.y, l.z, l.w];
  }

  /** Rebuilds parts, stubs, clips and ground for a new session; frames the camera. */
  load(scene: SceneData, hoseBounds: THREE.Box3): void {
    this.world.remove(this.content);
    disposeTree(this.content);
    this.content = new THREE.Group();
    this.world.add(this.content);

    const box = hoseBounds.clone();
    scene.parts.forEach((p, i) => {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(p.vertices, 3));
      g.setIndex(p.triangles);
      const flat = g.toNonIndexed();
      g.dispose();
      flat.computeVertexNormals();
      const m = surface({
        color: PART_COLOURS[i % PART_COLOURS.length],
        roughness: 0.75,
        metalness: 0.15,
        side: THREE.DoubleSide,
      });
      const mesh = new THREE.Mesh(flat, m);
      mesh.name = `part:${p.name}`;
      mesh.castShadow = true;
      mesh.receiveShadow = true;
      this.content.add(mesh);
      box.expandByPoint(new THREE.Vector3(...p.bounds_min));
      box.expandByPoint(new THREE.Vector3(...p.bounds_max));
    });
    this.fastenerObjects = (scene.fasteners ?? []).map((f) => {
      const object = f.kind === 'clip' ? clipMesh(f) : stubMesh(f);
      this.content.add(object);
      return { object, origin: f.origin, rest: object.quaternion.clone() };
    });
    if (box.isEmpty()) box.set(new THREE.Vector3(-0.5, -0.5, 0), new THREE.Vector3(0.5, 0.5, 0.5));
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    this.centre.copy(sphere.center);
    this.radius = Math.max(sphere.radius, 0.1);
    this.addGround(box);
    this.fitShadow();
    this.frame();
  }

  private addGround(box: THREE.Box3): void {
    const size = Math.max(box.max.x - box.min.x, box.max.y - box.min.y) * 3 + 1;
    const z = box.min.z - 0.002;
    const g = new THREE.Group();
    const plane = new THREE.Mesh(
      new THREE.PlaneGeometry(size, size),
      surface({ color: 0x3a4048, roughness: 1 }),
    );
    plane.receiveShadow = true;
    plane.position.set(this.centre.x, this.centre.y, z);
    g.add(plane);
    const grid = new THREE.GridHelper(size, Math.round(size / 0.1), 0x56606c, 0x4a525c);
    grid.rotation.x = Math.PI / 2; // GridHelper lies in xz; ours is the xy plane
    grid.position.set(this.centre.x, this.centre.y, z + 0.001);
    g.add(grid);
    g.name = 'ground';
    this.ground = g;
    this.content.add(g);
  }

  /** The sun's shadow covers the scene. */
  private fitShadow(): void {
    const c = this.toThree([this.centre.x, this.centre.y, this.centre.z]);
    const r = this.radius * 1.3;
    this.sun.target.position.copy(c);
    this.sun.position.copy(c).add(new THREE.Vector3(0.4, 1, 0.6).normalize().multiplyScalar(r * 3));
    const cam = this.sun.shadow.camera as THREE.OrthographicCamera;
    cam.left = cam.bottom = -r;
    cam.right = cam.top = r;
    cam.near = r * 0.5;
    cam.far = r * 6;
    cam.updateProjectionMatrix();
  }

  /** Points the camera at the scene from the front-left, above. */
  frame(): void {
    const c = this.toThree([this.centre.x, this.centre.y, this.centre.z]);
    const dist = this.radius / Math.sin((this.camera.fov * Math.PI) / 360) * 0.8;
    // from −x (the radiator side), −y (the left) and above, in the world frame
    const dir = new THREE.Vector3(-0.55, -0.7, 0.55).normalize();
    const eye = this.toThree([
      this.centre.x + dir.x * dist,
      this.centre.y + dir.y * dist,
      this.centre.z + dir.z * dist,
    ]);
    this.camera.position.copy(eye);
    this.camera.near = dist / 100;
    this.camera.far = dist * 20;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(c);
    this.controls.update();
    if (this.scene.fog instanceof THREE.Fog) {
      this.scene.fog.near = dist * 2;
      this.scene.fog.far = dist * 6;
    }
  }

  /** Draws the moving parts where a snapshot puts them: each part's mesh holds the scene's
   * placement, so its transform is the part's pose (the others keep the identity); the
   * stubs, connectors and clips on a moving part go with it. */
  setPartPoses(poses: readonly PartPose[]): void {
    const meshes = this.partMeshes();
    const turn = new THREE.Quaternion();
    for (const p of poses) {
      const m = meshes[p.part];
      if (m === undefined) continue;
      m.position.set(p.translation[0], p.translation[1], p.translation[2]);
      m.quaternion.set(p.rotation[0], p.rotation[1], p.rotation[2], p.rotation[3]);
      turn.set(p.rotation[0], p.rotation[1], p.rotation[2], p.rotation[3]);
      this.fastenerObjects.forEach((f, i) => {
        if (this.carriers[i] !== p.part) return;
        f.object.position.set(...carry(p, f.origin));
        f.object.quaternion.multiplyQuaternions(turn, f.rest);
      });
    }
  }

  /** Which part each fastener sits on (index into the welcome's parts, -1: none), in the
   *  welcome's order of `fasteners`; they follow those parts' poses from the next
   *  `setPartPoses`. */
  setFastenerCarriers(carriers: readonly number[]): void {
    this.carriers = [...carriers];
  }

  /** The stubs, connectors and clips as drawn (world frame): name and origin. */
  fastenersDrawn(): { name: string; origin: Vec3 }[] {
    return this.fastenerObjects.map((f) => ({ name: f.object.name, origin: [f.object.position.x, f.object.position.y, f.object.position.z] }));
  }

  /** Lights part `k` up (index into the welcome's parts; null: none). */
  highlightPart(k: number | null): void {
    this.partMeshes().forEach((m, i) => (m.material as SurfaceMaterial).emissive.setHex(i === k ? HIGHLIGHT_GLOW : 0x000000));
  }

  /** The rigid parts' meshes in the welcome's order (for picking surfaces: their world
   * transforms are the parts' poses). */
  partMeshes(): THREE.Mesh[] {
    return this.content.children.filter((c): c is THREE.Mesh => c.name.startsWith('part:') && (c as THREE.Mesh).isMesh);
  }

  /** A drag handle (TransformControls) of `size` in this stage: the view does not orbit
   *  while it is dragged; `dragging(on)` is told when a drag starts and ends. */
  handle(size: number, dragging: (on: boolean) => void): TransformControls {
    const gizmo = new TransformControls(this.camera, this.renderer.domElement);
    gizmo.setSize(size);
    this.scene.add(gizmo.getHelper());
    gizmo.addEventListener('dragging-changed', (e) => {
      const on = (e as unknown as { value: boolean }).value;
      this.controls.enabled = !on;
      dragging(on);
    });
    return gizmo;
  }

  get groundObject(): THREE.Object3D | null {
    return this.ground;
  }
}

function axisQuaternion(axis: Vec3): THREE.Quaternion {
  return new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 1, 0), new THREE.Vector3(...axis).normalize());
}

/** A stub: a cylinder from its mouth along the push-on axis, with a flange at its base. */
export function stubMesh(f: FastenerData): THREE.Object3D {
  const g = new THREE.Group();
  g.name = `stub:${f.name}`;
  const r = f.diameter / 2;
  const mat = surface({ color: 0xd0d4d8, metalness: 0.6, roughness: 0.35 });
  const body = new THREE.Mesh(new THREE.CylinderGeometry(r, r, f.length, 24), mat);
  body.position.y = f.length / 2;
  const flange = new THREE.Mesh(new THREE.CylinderGeometry(r * 1.6, r * 1.6, f.length * 0.12, 24), mat);
  flange.position.y = f.length;
  g.add(body, flange);
  g.position.set(...f.origin);
  g.quaternion.copy(axisQuaternion(f.axis));
  g.traverse((o) => (o.castShadow = true));
  return g;
}

/** A clip: an open ring around the seat, the gap facing the opening direction. */
export function clipMesh(f: FastenerData): THREE.Object3D {
  const r = f.diameter / 2;
  const gap = Math.min(Math.asin(Math.min(f.opening_width / f.diameter, 0.99)) * 2, Math.PI);
  const ring = new THREE.TorusGeometry(r + 0.003, 0.003, 8, 32, 2 * Math.PI - gap);
  const mat = surface({ color: 0xe0a030, roughness: 0.5 });
  const mesh = new THREE.Mesh(ring, mat);
  // Torus: in its xy plane, axis z, arc from +x counter-clockwise. Put the axis along the
  // hose direction and centre the gap on the opening direction.
  const l = new THREE.Vector3(...f.axis).normalize();
  const n = new THREE.Vector3(...f.opening);
  n.addScaledVector(l, -n.dot(l)).normalize();
  const m = l.clone().cross(n);
  // basis: x = direction at the start of the arc, z = l
  const start = n.clone().multiplyScalar(Math.cos(gap / 2)).addScaledVector(m, Math.sin(gap / 2));
  const y = l.clone().cross(start);
  const basis = new THREE.Matrix4().makeBasis(start, y, l);
  const g = new THREE.Group();
  g.name = `clip:${f.name}`;
  mesh.quaternion.setFromRotationMatrix(basis);
  mesh.castShadow = true;
  g.add(mesh);
  g.position.set(...f.origin);
  return g;
}

export function disposeTree(o: THREE.Object3D): void {
  o.traverse((c) => {
    const m = c as THREE.Mesh;
    if (m.geometry) m.geometry.dispose();
    const mat = m.material as THREE.Material | THREE.Material[] | undefined;
    if (Array.isArray(mat)) mat.forEach((x) => x.dispose());
    else mat?.dispose();
  });
}
