// How a hand holds the hose (protocol `grab.grip`): firm (six degrees of
// freedom), axial (position held; the hose may turn about its own axis in the hand) or
// ball (position held; free to turn about every axis). The panel sets the mouse's grip;
// a key held at the grab overrides it (F firm, A axial, B ball); each VR controller's
// A/X button cycles its own. Pure logic: no DOM, no three.js.

export type Grip = 'firm' | 'axial' | 'ball';

/** Every grip, in cycling order. */
export const GRIPS: readonly Grip[] = ['firm', 'axial', 'ball'];

/** The next grip after `g` (firm → axial → ball → firm). */
export function nextGrip(g: Grip): Grip {
  return GRIPS[(GRIPS.indexOf(g) + 1) % GRIPS.length];
}

/** Whether `s` names a grip. */
export function isGrip(s: unknown): s is Grip {
  return typeof s === 'string' && (GRIPS as readonly string[]).includes(s);
}

/** The grip a key selects while held at the grab (`KeyboardEvent.code`), or null. */
export function gripOfKey(code: string): Grip | null {
  switch (code) {
    case 'KeyF': return 'firm';
    case 'KeyA': return 'axial';
    case 'KeyB': return 'ball';
    default: return null;
  }
}

/** The grip of a grab: the newest grip key still held, else the panel's choice. */
export function gripFor(choice: Grip, heldKeys: Iterable<string>): Grip {
  let g: Grip | null = null;
  for (const k of heldKeys) g = gripOfKey(k) ?? g;
  return g ?? choice;
}

/** A short description for the panel and the controller label. */
export function gripLabel(g: Grip): string {
  switch (g) {
    case 'firm': return 'firm (6 DOF)';
    case 'axial': return 'axial (turns about its axis)';
    case 'ball': return 'ball (turns freely)';
  }
}
