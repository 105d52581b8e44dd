import { Emitter } from './emitter';
import type { ControlAction } from './protocol';

export type ConnectionState = 'connecting' | 'connected' | 'disconnected';

/**
 * The WebSocket URL for a page served at `http://HOST/TOKEN/...`: `ws://HOST/TOKEN/ws`.
 * The prefix is the page path up to and including its first segment (the session token).
 */
export function webSocketUrl(loc: Location = window.location): string {
  const first = loc.pathname.split('/').filter((p) => p.length > 0)[0];
  // A path like /TOKEN/index.html still has the token as its first segment; "/" has none.
  const prefix = first && !first.includes('.') ? `/${first}/` : '/';
  const scheme = loc.protocol === 'https:' ? 'wss' : 'ws';
  return `${scheme}://${loc.host}${prefix}ws`;
}

interface ConnectionEvents extends Record<string, unknown> {
  state: ConnectionState;
  /** One parsed JSON object from a message line. */
  message: unknown;
}

/**
 * The page's single WebSocket to the debug server. Each text message holds one or more JSON
 * objects separated by '\n'; lines that are empty or not valid JSON are skipped silently.
 * There is no reconnection: once closed the state stays "disconnected".
 */
export class Connection extends Emitter<ConnectionEvents> {
  state: ConnectionState = 'connecting';
  private ws: WebSocket | null = null;

  constructor(readonly url: string) {
    super();
  }

  open(): void {
    let ws: WebSocket;
    try {
      ws = new WebSocket(this.url);
    } catch {
      this.setState('disconnected');
      return;
    }
    this.ws = ws;
    ws.onopen = () => this.setState('connected');
    ws.onclose = () => this.setState('disconnected');
    ws.onerror = () => {
      /* a close event follows */
    };
    ws.onmessage = (ev) => {
      if (typeof ev.data !== 'string') return;
      let frames = 0;
      for (const line of ev.data.split('\n')) {
        if (line.trim().length === 0) continue;
        let obj: unknown;
        try {
          obj = JSON.parse(line);
        } catch {
          continue;
        }
        if ((obj as { type?: unknown }).type === 'frame') frames++;
        this.emit('message', obj);
      }
      // the server sends the next live frame once this one is taken (flow control)
      if (frames > 0 && ws.readyState === WebSocket.OPEN) ws.send('{"type":"ack"}');
    };
  }

  /** Sends `{"type": "control", "action": action}` if the socket is open. */
  control(action: ControlAction | string): void {
    if (this.ws && this.ws.readyState === WebSocket.OPEN) {
      this.ws.send(JSON.stringify({ type: 'control', action }));
    }
  }

  private setState(s: ConnectionState): void {
    if (this.state === s) return;
    this.state = s;
    this.emit('state', s);
  }
}
