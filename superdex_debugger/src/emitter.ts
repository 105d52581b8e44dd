/** A minimal typed event emitter. */
export class Emitter<Events extends Record<string, unknown>> {
  private handlers: { [K in keyof Events]?: ((arg: Events[K]) => void)[] } = {};

  on<K extends keyof Events>(name: K, fn: (arg: Events[K]) => void): void {
    (this.handlers[name] ??= []).push(fn);
  }

  emit<K extends keyof Events>(name: K, arg: Events[K]): void {
    for (const fn of this.handlers[name] ?? []) fn(arg);
  }
}
