import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { RoomEnvironment } from 'three/examples/jsm/environments/RoomEnvironment.js';
import { ActorVisual, type PickInfo } from './actorVisual';
import { ConstraintsView } from './constraintsView';
import { TendonsView } from './tendonsView';
import { ContactsView } from './contactsView';
import type { ActorMsg, Axes, FrameMsg } from './protocol';

/**
 * Software WebGL (SwiftShader, llvmpipe) rasterizes on the CPU that the page also needs for the
 * incoming messages: while the scene changes it renders at most every SOFTWARE_RENDER_INTERVAL ms
 * at SOFTWARE_PIXEL_RATIO, then once at full size when nothing changed for SOFTWARE_SETTLE ms.
 */
const SOFTWARE_RENDER_INTERVAL = 300;
const SOFTWARE_PIXEL_RATIO = 0.75;
const SOFTWARE_SETTLE = 500;

/** Clear colour of the view; the fog fades to it. */
const BACKGROUND = '#1b1f27';

/**
 * The 3D view: renderer, camera with orbit controls, lights, ground grid, the visuals of the
 * shown scene's actors and its contacts. World coordinates are the engine's (m); the camera's
 * up axis is +z for FLU and +y for RUB. Renders only when something changed.
 */
export class SceneView {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera = new THREE.PerspectiveCamera(40, 1, 0.005, 500);
  controls: OrbitControls;
  /** Called when the user clicks an actor (or empty space: null). */
  onPick: (p: PickInfo | null) => void = () => {};

  private axes: Axes = 'FLU';
  private readonly actorsRoot = new THREE.Group();
  private readonly visuals = new Map<number, ActorVisual>();
  private readonly contacts = new ContactsView();
  private readonly constraints = new ConstraintsView();
  private readonly tendons = new TendonsView();
  private grid: THREE.GridHelper | null = null;
  private readonly hemi = new THREE.HemisphereLight('#dfe8ff', '#2a2e36', 1.6);
  private readonly sun = new THREE.DirectionalLight('#ffffff', 2.4);
  private readonly fog = new THREE.Fog(BACKGROUND, 10, 40);
  private dirty = true;
  /** Software WebGL: rendering costs the CPU that the page needs for the messages. */
  private readonly software: boolean;
  /** Earliest time of the next render, ms (performance.now clock). */
  private nextRender = 0;
  private lastRender = 0;
  /** Number of times the view has been drawn (for tests and diagnostics). */
  private draws = 0;
  /** Software WebGL: false while drawing at reduced resolution. */
  private fullQuality = true;
  private fitted = false;
  private framesVisible = false;
  /** Also draw the colliders of links shown with a render model. */
  private collidersOverModels = false;
  private envMap: THREE.Texture | null = null;
  private selection: { actor?: number; link?: number } = {};
  private lastFrame: FrameMsg | undefined;
  /** Radius of the fitted scene, m: sets the size of grid cells, frames and contact markers. */
  private radius = 1;

  constructor(private readonly container: HTMLElement) {
    // preserveDrawingBuffer lets tests and screenshots read the canvas back at any time.
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.scene.background = new THREE.Color(BACKGROUND);
    this.scene.fog = this.fog;
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFShadowMap;
    container.appendChild(this.renderer.domElement);

    // Software WebGL (SwiftShader, llvmpipe: headless browsers, VMs) renders on the CPU: draw
    // less often and with a smaller shadow map so that the page keeps up with the messages.
    const software = isSoftwareRenderer(this.renderer.getContext());
    this.software = software;
    this.sun.castShadow = true;
    this.sun.shadow.mapSize.setScalar(software ? 1024 : 2048);
    this.sun.shadow.bias = -0.0004;
    this.sun.shadow.normalBias = 0.01;
    this.scene.add(this.hemi, this.sun, this.sun.target, this.actorsRoot, this.contacts.root, this.constraints.root, this.tendons.root);

    this.controls = this.makeControls();
    this.setAxes('FLU');
    this.installPicking();
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    const loop = (now: number) => {
      // The next frame is requested first, so that a failing render cannot stop the loop.
      requestAnimationFrame(loop);
      this.controls.update();
      if (this.dirty && now >= this.nextRender) {
        this.dirty = false;
        // While the scene keeps changing, a CPU rasterizer draws at a reduced size and rate.
        if (this.software) {
          this.setQuality(false);
          this.nextRender = now + SOFTWARE_RENDER_INTERVAL;
        }
        this.draw();
        this.lastRender = now;
      } else if (this.software && !this.fullQuality && !this.dirty && now - this.lastRender > SOFTWARE_SETTLE) {
        // Once it has settled, one render at full size.
        this.setQuality(true);
        this.draw();
        this.lastRender = now;
      }
    };
    requestAnimationFrame(loop);
  }

  private makeControls(): OrbitControls {
    const c = new OrbitControls(this.camera, this.renderer.domElement);
    c.enableDamping = true;
    c.dampingFactor = 0.15;
    c.addEventListener('change', () => this.requestRender());
    return c;
  }

  /** Z up for FLU (the default), Y up for RUB. */
  setAxes(axes: Axes): void {
    this.axes = axes === 'RUB' ? 'RUB' : 'FLU';
    const up = this.upVector();
    this.camera.up.copy(up);
    this.hemi.position.copy(up);
    // OrbitControls reads camera.up when constructed.
    const target = this.controls.target.clone();
    this.controls.dispose();
    this.controls = this.makeControls();
    this.controls.target.copy(target);
    this.rebuildGrid();
    if (this.fitted) this.fit();
    this.requestRender();
  }

  /** The axis convention the view shows. */
  upAxis(): Axes {
    return this.axes;
  }

  private upVector(): THREE.Vector3 {
    return this.axes === 'RUB' ? new THREE.Vector3(0, 1, 0) : new THREE.Vector3(0, 0, 1);
  }

  /** A FLU direction (forward, left, up) in the world axes of the session. */
  private fluToWorld(f: number, l: number, u: number): THREE.Vector3 {
    return this.axes === 'RUB' ? new THREE.Vector3(-l, u, -f) : new THREE.Vector3(f, l, u);
  }

  private rebuildGrid(): void {
    if (this.grid) {
      this.grid.removeFromParent();
      this.grid.dispose();
    }
    // Cells of a round size (0.01, 0.1, 1 m ...) about a quarter of the scene radius.
    const cell = Math.pow(10, Math.round(Math.log10(Math.max(this.radius, 1e-3) * 0.25)));
    const cells = 60;
    this.grid = new THREE.GridHelper(cell * cells, cells, '#4d5666', '#2b313b');
    const mat = this.grid.material as THREE.Material;
    mat.transparent = true;
    mat.opacity = 0.85;
    if (this.axes === 'FLU') this.grid.rotation.x = Math.PI / 2;
    this.scene.add(this.grid);
  }

  /** Shows exactly these actors (adds new ones, drops missing or re-described ones). */
  setActors(actors: ActorMsg[], colorOf: (a: ActorMsg) => string): void {
    const keep = new Set<number>();
    for (const a of actors) {
      keep.add(a.handle);
      const v = this.visuals.get(a.handle);
      if (v && v.desc === a) continue;
      v?.dispose();
      const nv = new ActorVisual(a, colorOf(a));
      nv.setFramesVisible(this.framesVisible);
      nv.setCollidersOverModels(this.collidersOverModels);
      // Render models load asynchronously.
      nv.onChange = () => this.requestRender();
      nv.modelEnvironment = () => this.modelEnvironment();
      nv.setFrameSize(this.radius * 0.25);
      nv.applyFrame(this.lastFrame);
      this.visuals.set(a.handle, nv);
      this.actorsRoot.add(nv.root);
    }
    for (const [h, v] of this.visuals) {
      if (!keep.has(h)) {
        v.dispose();
        this.visuals.delete(h);
      }
    }
    this.applySelection();
    this.requestRender();
  }

  /** Handles of the actors drawn. */
  shownActors(): number[] {
    return [...this.visuals.keys()];
  }

  /** Fits the camera again on the next frame (another scene is shown). */
  refit(): void {
    this.fitted = false;
    this.lastFrame = undefined;
  }

  /** Poses, soft nodes and contacts of this frame; fits the camera on the first one. */
  applyFrame(frame: FrameMsg | undefined): void {
    this.lastFrame = frame;
    for (const v of this.visuals.values()) v.applyFrame(frame);
    this.contacts.update(frame?.contacts);
    this.constraints.update(frame?.constraints);
    this.tendons.update(frame?.tendons);
    if (!this.fitted && frame && this.visuals.size > 0) {
      this.fitted = true;
      this.fit();
    }
    this.requestRender();
  }

  setSelection(actor?: number, link?: number): void {
    this.selection = { actor, link };
    this.applySelection();
    this.requestRender();
  }

  private applySelection(): void {
    for (const [h, v] of this.visuals) v.setHighlight(h === this.selection.actor, this.selection.link);
  }

  setFramesVisible(v: boolean): void {
    this.framesVisible = v;
    for (const a of this.visuals.values()) a.setFramesVisible(v);
    this.requestRender();
  }

  /** Draws the colliders of links that have a render model too (semi-transparent, over the model). */
  setCollidersVisible(v: boolean): void {
    this.collidersOverModels = v;
    for (const a of this.visuals.values()) a.setCollidersOverModels(v);
    this.requestRender();
  }

  /**
   * The environment map of render models' physically based materials (without one, metallic
   * surfaces reflect only the two lights and look black), made when the first model is shown.
   * Not the scene's environment: that would also light the colliders' Phong and Lambert materials.
   */
  private modelEnvironment(): THREE.Texture {
    if (!this.envMap) {
      const pmrem = new THREE.PMREMGenerator(this.renderer);
      const room = new RoomEnvironment();
      this.envMap = pmrem.fromScene(room, 0.04).texture;
      room.dispose();
      pmrem.dispose();
    }
    return this.envMap;
  }

  /** Links of the shown actors whose render model has loaded and is in the scene. */
  /** Draws the scene now. */
  private draw(): void {
    this.renderer.render(this.scene, this.camera);
    this.draws++;
  }

  /** Number of times the view has been drawn since the page loaded. */
  drawCount(): number {
    return this.draws;
  }

  renderModelCount(): number {
    let n = 0;
    for (const v of this.visuals.values()) n += v.renderModelCount();
    return n;
  }

  /** True if a shown actor has a link with a render model (loaded or not). */
  hasRenderModels(): boolean {
    for (const v of this.visuals.values()) if (v.hasRenderModels) return true;
    return false;
  }

  setContactsVisible(v: boolean): void {
    this.contacts.root.visible = v;
    this.requestRender();
  }

  setConstraintsVisible(v: boolean): void {
    this.constraints.root.visible = v;
    this.requestRender();
  }

  setTendonsVisible(v: boolean): void {
    this.tendons.root.visible = v;
    this.requestRender();
  }

  /** Force arrow length per newton, m/N. */
  setForceScale(mPerN: number): void {
    this.contacts.scale = mPerN;
    this.contacts.update(this.lastFrame?.contacts);
    this.requestRender();
  }

  /** Frames the camera on the actors (planes excluded) and sizes grid, light and markers. */
  fit(): void {
    const box = new THREE.Box3();
    for (const v of this.visuals.values()) v.expandBox(box);
    const center = new THREE.Vector3();
    if (box.isEmpty()) {
      this.radius = 1;
    } else {
      box.getCenter(center);
      this.radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 0.05);
    }
    const r = this.radius;
    // Fit the bounding sphere in the narrower of the vertical and horizontal fields of view.
    const vHalf = THREE.MathUtils.degToRad(this.camera.fov / 2);
    const hHalf = Math.atan(Math.tan(vHalf) * this.camera.aspect);
    const dist = (r / Math.sin(Math.min(vHalf, hHalf))) * 1.3;
    const dir = this.fluToWorld(0.45, -1, 0.5).normalize();
    this.camera.position.copy(center).addScaledVector(dir, dist);
    this.camera.near = dist / 200;
    this.camera.far = dist * 100;
    // Fog fades the ground and grid into the background towards the horizon.
    this.fog.near = dist * 1.0;
    this.fog.far = dist * 3.2;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();

    // Sun from above and to the side, its shadow box covering the scene with margin.
    this.sun.position.copy(center).add(this.fluToWorld(1.2, 0.8, 3).multiplyScalar(r * 2));
    this.sun.target.position.copy(center);
    const cam = this.sun.shadow.camera;
    cam.left = cam.bottom = -r * 2.5;
    cam.right = cam.top = r * 2.5;
    cam.near = 0.01 * r;
    cam.far = r * 20;
    cam.updateProjectionMatrix();

    this.contacts.pointRadius = r * 0.012;
    this.contacts.maxLength = r * 1.2;
    this.contacts.update(this.lastFrame?.contacts);
    this.constraints.pointRadius = r * 0.025;
    this.constraints.update(this.lastFrame?.constraints);
    for (const v of this.visuals.values()) v.setFrameSize(r * 0.25);
    this.rebuildGrid();
    this.requestRender();
  }

  /** Software WebGL: full resolution, or SOFTWARE_PIXEL_RATIO while the scene changes. */
  private setQuality(full: boolean): void {
    if (full === this.fullQuality) return;
    this.fullQuality = full;
    this.renderer.setPixelRatio(full ? Math.min(window.devicePixelRatio, 2) : SOFTWARE_PIXEL_RATIO);
  }

  requestRender(): void {
    this.dirty = true;
  }

  private resize(): void {
    const w = Math.max(this.container.clientWidth, 1);
    const h = Math.max(this.container.clientHeight, 1);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    // Resizing clears the drawing buffer: draw again at once rather than leave the view blank
    // until the next scheduled render.
    this.draw();
    this.requestRender();
  }

  /** A click (a press and release without dragging) selects the actor under the pointer. */
  private installPicking(): void {
    const el = this.renderer.domElement;
    let down: { x: number; y: number } | null = null;
    el.addEventListener('pointerdown', (e) => (down = { x: e.clientX, y: e.clientY }));
    el.addEventListener('pointerup', (e) => {
      if (!down || Math.hypot(e.clientX - down.x, e.clientY - down.y) > 4) return;
      down = null;
      const rect = el.getBoundingClientRect();
      const ndc = new THREE.Vector2(((e.clientX - rect.left) / rect.width) * 2 - 1, -((e.clientY - rect.top) / rect.height) * 2 + 1);
      const ray = new THREE.Raycaster();
      ray.setFromCamera(ndc, this.camera);
      // The raycaster also hits hidden objects (colliders under a render model): skip them.
      const hit = ray.intersectObject(this.actorsRoot, true).find((h) => h.object.userData.pick && shown(h.object));
      this.onPick(hit ? (hit.object.userData.pick as PickInfo) : null);
    });
  }
}

/** True if the object and all its ancestors are visible. */
function shown(o: THREE.Object3D | null): boolean {
  for (; o; o = o.parent) if (!o.visible) return false;
  return true;
}

/** True when WebGL runs on a CPU rasterizer. */
function isSoftwareRenderer(gl: WebGLRenderingContext | WebGL2RenderingContext): boolean {
  const ext = gl.getExtension('WEBGL_debug_renderer_info');
  const name = String(ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER));
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}
