// Pliant's browser/VR viewer: connects to the `pliant serve` that served this
// page, draws the session (parts, stubs, clips, hoses as force-coloured tubes), lets the
// mouse or VR controllers grab and move hoses and the panel move parts, and shows loads,
// limits, the verdict and its findings. Colour modes with a legend (hand load, bend radius
// vs minimum, twist, axial force), markers at the installation checks' violations,
// tolerance envelopes (dropped files or `?envelope=URL`). `?xr=emulate` installs an
// emulated headset (iwer) for tests and development. The viewer itself is `App` (app.ts).

import './style.css';
import { App } from './app';

async function main(): Promise<void> {
  const params = new URLSearchParams(location.search);
  if (params.get('xr') === 'emulate') {
    const { XRDevice, metaQuest3 } = await import('iwer');
    const device = new XRDevice(metaQuest3);
    device.installRuntime({ forceInstall: true });
    (window as unknown as { pliantXrDevice: unknown }).pliantXrDevice = device;
  }
  const app = new App(document.getElementById('app') as HTMLElement, document.getElementById('view') as HTMLElement, params);
  app.start();
}

void main();
