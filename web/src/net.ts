// The WebSocket connection to `pliant serve` (protocol v1, docs/protocol.md): sends
// `hello`, hands every server message to the listeners, and keeps a record of each `move`
// sent so that the latency until the snapshot (and the frame) that shows it can be
// measured.

import type { ClientMessage, ErrorMessage, ReportMessage, SceneSourceMessage, Snapshot, Vec3, Welcome } from './protocol';

export interface NetListener {
  welcome(w: Welcome, raw: string): void;
  snapshot(s: Snapshot, raw: string): void;
  error(e: ErrorMessage): void;
  report(r: ReportMessage): void;
  sceneSource(m: SceneSourceMessage): void;
  status(text: string, connected: boolean): void;
}

/** One `move` in flight: when it was sent and where to. */
export interface PendingMove {
  handId: number;
  target: Vec3;
  sentAt: number;
  snapshotAt?: number;
  frameAt?: number;
}

export class Net {
  private ws: WebSocket | null = null;
  private closedByUser = false;
  clientId = 0;
  /** Moves waiting for the snapshot (and frame) that shows them; bounded. */
  readonly pending: PendingMove[] = [];
  /** Moves whose snapshot and frame were seen (latency samples), bounded. */
  readonly done: PendingMove[] = [];
  trackLatency = true;

  constructor(private readonly url: string, private readonly listener: NetListener) {}

  connect(): void {
    this.closedByUser = false;
    const ws = new WebSocket(this.url);
    this.ws = ws;
    this.listener.status('connecting…', false);
    ws.onopen = () => {
      this.send({ type: 'hello', version: 1 });
      this.listener.status('connected', true);
    };
    ws.onmessage = (ev: MessageEvent) => {
      if (typeof ev.data !== 'string') return;
      let msg: { type?: string };
      try {
        msg = JSON.parse(ev.data) as { type?: string };
      } catch {
        return;
      }
      if (msg.type === 'snapshot') {
        const s = msg as Snapshot;
        this.matchSnapshot(s);
        this.listener.snapshot(s, ev.data);
      } else if (msg.type === 'welcome') {
        const w = msg as Welcome;
        this.clientId = w.client_id;
        this.pending.length = 0;
        this.listener.welcome(w, ev.data);
      } else if (msg.type === 'error') {
        this.listener.error(msg as ErrorMessage);
      } else if (msg.type === 'report') {
        this.listener.report(msg as ReportMessage);
      } else if (msg.type === 'scene_source') {
        this.listener.sceneSource(msg as SceneSourceMessage);
      }
    };
    ws.onclose = () => {
      this.listener.status('disconnected — reconnecting…', false);
      if (!this.closedByUser) setTimeout(() => this.connect(), 1000);
    };
  }

  close(): void {
    this.closedByUser = true;
    this.ws?.close();
  }

  get open(): boolean {
    return this.ws !== null && this.ws.readyState === WebSocket.OPEN;
  }

  send(msg: ClientMessage): boolean {
    if (!this.open || this.ws === null) return false;
    this.ws.send(JSON.stringify(msg));
    if (msg.type === 'move' && this.trackLatency) {
      this.pending.push({ handId: msg.hand_id, target: [...msg.position], sentAt: performance.now() });
      if (this.pending.length > 64) this.pending.shift();
    }
    return true;
  }

  /** Marks pending moves whose target a snapshot's hand shows. */
  private matchSnapshot(s: Snapshot): void {
    if (this.pending.length === 0) return;
    const now = performance.now();
    for (const p of this.pending) {
      if (p.snapshotAt !== undefined) continue;
      const h = s.hands.find((x) => x.hand_id === p.handId);
      if (h === undefined) continue;
      const t = h.target;
      const d = Math.abs(t[0] - p.target[0]) + Math.abs(t[1] - p.target[1]) + Math.abs(t[2] - p.target[2]);
      if (d < 1e-9) {
        // this snapshot shows this move, and every earlier one of the same hand
        for (const q of this.pending) {
          if (q.handId === p.handId && q.sentAt <= p.sentAt && q.snapshotAt === undefined) q.snapshotAt = now;
        }
      }
    }
  }

  /** Called right after a frame was drawn that used the newest snapshot. */
  frameDrawn(now: number): void {
    for (let i = 0; i < this.pending.length; ) {
      const p = this.pending[i];
      if (p.snapshotAt !== undefined) {
        p.frameAt = now;
        this.done.push(p);
        if (this.done.length > 1000) this.done.shift();
        this.pending.splice(i, 1);
      } else {
        i++;
      }
    }
  }
}
