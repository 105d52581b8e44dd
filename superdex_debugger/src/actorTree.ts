import { esc } from './format';
import type { ActorMsg } from './protocol';
import type { Selection } from './selection';
import type { DebugStore } from './store';

/** Short label of an actor kind for the tree. */
const KIND_LABEL: Record<string, string> = { static: 'static', rigid: 'rigid', articulated: 'artic.', soft: 'soft' };

/**
 * The scene tree: scenes → actors → links. Rows carry data-scene / data-actor / data-link
 * attributes; clicking a row selects it, clicking the caret folds it.
 */
export class ActorTree {
  private readonly folded = new Set<string>();
  private selection: Selection | null = null;

  constructor(
    private readonly el: HTMLElement,
    private readonly store: DebugStore,
    private readonly colorOf: (a: ActorMsg) => string,
    private readonly onSelect: (s: Selection) => void,
  ) {
    el.addEventListener('click', (e) => this.onClick(e));
  }

  /** Rebuilds the tree from the store. */
  render(): void {
    const parts: string[] = [];
    for (const s of this.store.scenes.values()) {
      const sk = `s${s.handle}`;
      parts.push(`<li class="node scene ${this.folded.has(sk) ? 'folded' : ''}">`);
      parts.push(this.row(sk, 'scene', { scene: s.handle }, s.name, '', undefined, s.actors.size > 0));
      parts.push('<ul>');
      for (const a of s.actors.values()) {
        const ak = `a${s.handle}.${a.handle}`;
        const links = a.links ?? [];
        parts.push(`<li class="node actor ${this.folded.has(ak) ? 'folded' : ''}">`);
        parts.push(
          this.row(ak, 'actor', { scene: s.handle, actor: a.handle }, a.name ?? `actor ${a.handle}`, KIND_LABEL[a.kind] ?? a.kind, this.colorOf(a), links.length > 0),
        );
        if (links.length) {
          parts.push('<ul>');
          for (const l of links) {
            parts.push('<li class="node link">');
            parts.push(this.row(`l${l.handle}`, 'link', { scene: s.handle, actor: a.handle, link: l.handle }, l.name ?? `link ${l.handle}`, l.joint?.type ?? '', undefined, false));
            parts.push('</li>');
          }
          parts.push('</ul>');
        }
        parts.push('</li>');
      }
      parts.push('</ul></li>');
    }
    this.el.innerHTML = parts.length ? `<ul class="tree-root">${parts.join('')}</ul>` : '<div class="empty">Waiting for the scene…</div>';
    this.markSelection();
  }

  private row(key: string, kind: string, sel: Selection, name: string, meta: string, color: string | undefined, foldable: boolean): string {
    const data = `data-key="${key}" data-scene="${sel.scene}"` + (sel.actor !== undefined ? ` data-actor="${sel.actor}"` : '') + (sel.link !== undefined ? ` data-link="${sel.link}"` : '');
    const caret = foldable ? '<span class="caret"></span>' : '<span class="caret none"></span>';
    const icon = color ? `<span class="swatch" style="background:${color}"></span>` : `<span class="icon ${kind}"></span>`;
    return `<div class="row ${kind}" ${data}>${caret}${icon}<span class="name" title="${esc(name)}">${esc(name)}</span><span class="meta">${esc(meta)}</span></div>`;
  }

  setSelection(sel: Selection | null): void {
    this.selection = sel;
    this.markSelection();
  }

  private markSelection(): void {
    const s = this.selection;
    for (const row of this.el.querySelectorAll<HTMLElement>('.row')) {
      const d = row.dataset;
      const on = !!s && Number(d.scene) === s.scene && (d.actor === undefined ? s.actor === undefined : Number(d.actor) === s.actor) && (d.link === undefined ? s.link === undefined : Number(d.link) === s.link);
      row.classList.toggle('selected', on);
      if (on) row.scrollIntoView({ block: 'nearest' });
    }
  }

  /** All actor and link names shown in the tree. */
  names(): string[] {
    const out: string[] = [];
    for (const s of this.store.scenes.values()) {
      for (const a of s.actors.values()) {
        out.push(a.name ?? `actor ${a.handle}`);
        for (const l of a.links ?? []) out.push(l.name ?? `link ${l.handle}`);
      }
    }
    return out;
  }

  private onClick(e: MouseEvent): void {
    const target = e.target as HTMLElement;
    const row = target.closest<HTMLElement>('.row');
    if (!row) return;
    const d = row.dataset;
    if (target.classList.contains('caret') && !target.classList.contains('none')) {
      const key = d.key!;
      if (this.folded.has(key)) this.folded.delete(key);
      else this.folded.add(key);
      row.parentElement!.classList.toggle('folded');
      return;
    }
    this.onSelect({
      scene: Number(d.scene),
      actor: d.actor !== undefined ? Number(d.actor) : undefined,
      link: d.link !== undefined ? Number(d.link) : undefined,
    });
  }
}
