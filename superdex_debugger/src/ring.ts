/**
 * A bounded FIFO that keeps the latest `capacity` items.
 *
 * Items have an absolute index (0 for the first item ever pushed) that stays valid while the
 * item is stored; `start` is the absolute index of the oldest stored item.
 */
export class Ring<T> {
  private items: (T | undefined)[];
  private head = 0; // slot of the oldest item
  private count = 0;
  /** Absolute index of the oldest stored item. */
  start = 0;

  constructor(readonly capacity: number) {
    this.items = new Array(capacity);
  }

  get length(): number {
    return this.count;
  }

  /** Absolute index one past the newest item. */
  get end(): number {
    return this.start + this.count;
  }

  push(item: T): void {
    if (this.count < this.capacity) {
      this.items[(this.head + this.count) % this.capacity] = item;
      this.count++;
    } else {
      this.items[this.head] = item;
      this.head = (this.head + 1) % this.capacity;
      this.start++;
    }
  }

  /** The k-th stored item (0 = oldest), or undefined. */
  get(k: number): T | undefined {
    if (!Number.isInteger(k) || k < 0 || k >= this.count) return undefined;
    return this.items[(this.head + k) % this.capacity];
  }

  /** The item with absolute index `abs`, or undefined when dropped or not yet pushed. */
  getAbs(abs: number): T | undefined {
    return this.get(abs - this.start);
  }

  last(): T | undefined {
    return this.get(this.count - 1);
  }

  clear(): void {
    this.items = new Array(this.capacity);
    this.head = 0;
    this.count = 0;
    this.start = 0;
  }
}
