// The viewer's mode and how it changes: `live` draws the session and lets the mouse and
// the VR controllers pull hoses and the panel move parts; `replay` draws a recording
// (nothing is sent to the session); `author` edits the session's scene (docs/authoring.md)
// over the live drawing, hands at rest. Pure (unit-tested in node).

export type Mode = 'live' | 'replay' | 'author';

/** What asks the mode to change: a recording opened, "Back to live", the Author button. */
export type ModeEvent = 'replay' | 'live' | 'toggle_author';

/**
 * The mode after `event` in `mode`. A replay started while authoring ends the authoring,
 * and authoring started during a replay ends the replay: the author edits the live
 * session's scene, so it works over the live drawing. "Back to live" leaves a replay
 * only.
 */
export function nextMode(mode: Mode, event: ModeEvent): Mode {
  switch (event) {
    case 'replay':
      return 'replay';
    case 'live':
      return mode === 'replay' ? 'live' : mode;
    case 'toggle_author':
      return mode === 'author' ? 'live' : 'author';
  }
}

/** The newest live snapshot is drawn (not a recording's). */
export const drawsLive = (mode: Mode): boolean => mode !== 'replay';

/** Hands may grab hoses and the panel's controls may move parts. */
export const handsAct = (mode: Mode): boolean => mode === 'live';
