// Junction bodies (moulded T and Y pieces joining hose ends) without a shape of their
// own: a hub at the mean of the outlets with an arm out to each, moved to where the outlet
// nodes are in every snapshot (live and in replays). Shared geometry; per snapshot only
// transforms change. A body with a shape is drawn as its part, posed by `part_poses`.

import * as THREE from 'three';
import { drawnAsHub, hubRadius, junctionPose } from './junction_geometry';
import { surface } from './materials';
import type { JunctionBodyData, Vec3 } from './protocol';

const BODY_COLOUR = 0x6b7480;
const Y = new THREE.Vector3(0, 1, 0);

interface Drawn {
  data: JunctionBodyData;
  hub: THREE.Mesh;
  arms: THREE.Mesh[];
}

export class JunctionBodies {
  readonly group = new THREE.Group();
  private readonly drawn: Drawn[] = [];
  private readonly sphere = new THREE.SphereGeometry(1, 16, 12);
  private readonly cylinder = new THREE.CylinderGeometry(1, 1, 1, 12, 1);
  private readonly material = surface({ color: BODY_COLOUR, roughness: 0.5, metalness: 0.1 });
  private readonly dir = new THREE.Vector3();

  /** `radii`: per hose, its outer radius at each node [m]. */
  constructor(bodies: JunctionBodyData[], radii: number[][]) {
    this.group.name = 'junction_bodies';
    // a body with a shape is drawn as its part (posed with the parts)
    for (const data of bodies.filter(drawnAsHub)) {
      const outletRadii = data.outlets.map((o) => radii[o.hose]?.[o.node] ?? 0);
      const hub = new THREE.Mesh(this.sphere, this.material);
      hub.name = `junction:${data.name}`;
      hub.scale.setScalar(hubRadius(outletRadii));
      hub.castShadow = true;
      const arms = data.outlets.map((_, k) => {
        const arm = new THREE.Mesh(this.cylinder, this.material);
        arm.name = `junction:${data.name}:outlet:${k}`;
        arm.userData.radius = 1.2 * Math.max(outletRadii[k], 0.001);
        arm.castShadow = true;
        return arm;
      });
      this.group.add(hub, ...arms);
      this.drawn.push({ data, hub, arms });
    }
  }

  /** Moves every body to its outlets; `node(h, i)`: node i of hose h (world frame). */
  update(node: (hose: number, i: number) => Vec3 | null): void {
    for (const d of this.drawn) {
      const points: Vec3[] = [];
      for (const o of d.data.outlets) {
        const p = node(o.hose, o.node);
        if (p !== null) points.push(p);
      }
      if (points.length !== d.data.outlets.length) continue;
      const pose = junctionPose(points);
      d.hub.position.set(...pose.centre);
      pose.arms.forEach((a, k) => {
        const arm = d.arms[k];
        const r = arm.userData.radius as number;
        arm.visible = a.length > 0;
        this.dir.set(...a.direction);
        arm.quaternion.setFromUnitVectors(Y, this.dir);
        arm.scale.set(r, Math.max(a.length, 1e-6), r);
        arm.position.set(
          pose.centre[0] + 0.5 * a.length * a.direction[0],
          pose.centre[1] + 0.5 * a.length * a.direction[1],
          pose.centre[2] + 0.5 * a.length * a.direction[2],
        );
      });
    }
  }

  /** How many bodies are drawn. */
  get count(): number {
    return this.drawn.length;
  }

  dispose(): void {
    this.sphere.dispose();
    this.cylinder.dispose();
    this.material.dispose();
  }
}
