/**
 * Types of the messages exchanged with the debug server (protocol version 1).
 *
 * Server-to-page bodies are the lines of a recording (see docs/recording_format.md) plus
 * `session`, `end` and `status`. Units are SI (m, s, kg, N), positions and forces are in the
 * world frame, quaternions are [x, y, z, w]. Every field the page does not know is ignored.
 */

/** A 3-vector, e.g. a position (m), a unit normal, or a force (N). */
export type Vec3 = [number, number, number];

/** A pose [px, py, pz, qx, qy, qz, qw]: position in m, unit quaternion [x, y, z, w]. */
export type Pose = [number, number, number, number, number, number, number];

/** World axis convention: FLU = x forward, y left, z up; RUB = x right, y up, z back. */
export type Axes = 'FLU' | 'RUB';

/** First message of a connection. */
export interface SessionMsg {
  type: 'session';
  mode: 'live' | 'replay';
  version: number;
  axes?: Axes;
  /** The recording's file name (replay) or "" (live). */
  source?: string;
}

/** First line of a recording. */
export interface HeaderMsg {
  type: 'header';
  format?: string;
  version?: number;
  units?: string;
  /** Simulated time between frames, s (0 = every step). */
  frameInterval?: number;
}

/** Describes a scene before its first frame. */
export interface SceneMsg {
  type: 'scene';
  scene: number;
  name?: string;
  /** Gravity, m/s^2, world frame. */
  gravity?: Vec3;
}

/** Collision shape, spelled as in `.superdex_bot` files; exactly one key is set. */
export interface Shape {
  /** Sphere of `radius` (m) centred at `center` (m, shape frame). */
  sphere?: { radius: number; center?: Vec3 };
  /** Box with half extents (m) along the shape's x, y, z. */
  box?: { halfExtents: Vec3 };
  /** Capsule along the shape's z: cylinder of half length `halfLength` plus two caps (m). */
  capsule?: { radius: number; halfLength: number };
  /** Infinite plane {x : normal . x = distance} in the shape frame (normal of any length). */
  plane?: { normal: Vec3; distance: number };
  /** Triangle mesh: vertices (m, shape frame) as [[x,y,z],...] or flat; triangles as [[i,j,k],...] or flat. */
  mesh?: { vertices: number[][] | number[]; triangles: number[][] | number[] };
}

/** A collider attached to a link. */
export interface Collider {
  shape: Shape;
  /** Pose of the shape in its link's frame. */
  linkFromShape?: Pose;
}

/** The joint that connects a link to its parent. */
export interface Joint {
  /** "Hard", "Free", "Revolute", "Prismatic" or "Spherical" (the bot files' spelling). */
  type: string;
  /** Number of generalized velocities of the joint. */
  dofs: number;
  /** Index of the joint's first DOF in the actor's qd. */
  offset: number;
}

/**
 * A glTF model drawn for a link instead of its colliders. The model is in the link frame:
 * scaled by `scale`, then placed at the link's world pose (not at a collider's linkFromShape).
 */
export interface RenderModel {
  /** File name, for display (e.g. "ball.glb"). */
  name?: string;
  /** Scale along the link's x, y, z applied to the model. */
  scale?: Vec3;
  /** The whole .glb file, base64. */
  glb: string;
}

/** A link of a rigid, articulated or static actor. */
export interface LinkDesc {
  handle: number;
  name?: string;
  /** Index of the parent link in the actor's `links`, -1 for the root. */
  parent: number;
  colliders?: Collider[];
  /** Link mass, kg (optional). */
  mass?: number;
  joint?: Joint;
  /** Optional glTF model of the link (never on soft actors). */
  renderModel?: RenderModel;
}

export type ActorKind = 'static' | 'rigid' | 'articulated' | 'soft';

/** Describes an actor before the first frame that contains it. */
export interface ActorMsg {
  type: 'actor';
  scene: number;
  handle: number;
  name?: string;
  kind: ActorKind | string;
  links?: LinkDesc[];
  /** Soft bodies: node positions when first seen, m, world frame. */
  nodes?: Vec3[];
  /** Soft bodies: surface triangles (node indices, counter-clockwise seen from outside). */
  surfaceTriangles?: [number, number, number][];
  /** Number of generalized velocities (articulated and rigid). */
  numDofs?: number;
}

/** An actor described earlier is gone. */
export interface DestroyMsg {
  type: 'destroy';
  scene: number;
  handle: number;
}

/** A contact between two bodies (link, rigid or soft actor handles). */
export interface Contact {
  a: number;
  b: number;
  /** Contact point, m, world frame. */
  p: Vec3;
  /** Unit normal from b towards a, world frame. */
  n: Vec3;
  /** Force on a, N, world frame (b receives -f). */
  f: Vec3;
}

/** A constraint as drawn: its point on its first actor and its target or its point on the second. */
export interface ConstraintMarker {
  /** The constraint's handle. */
  h: number;
  /** Its type, e.g. "RIGID_SPHERICAL_JOINT". */
  type: string;
  /** m, world frame. */
  a: Vec3;
  b: Vec3;
}

/** Generalized positions and velocities of one actor. */
export interface JointState {
  q: number[];
  qd: number[];
}

/** State of a scene after a step. */
/** A spatial tendon of an articulated actor: its segments, flat [ax, ay, az, bx, by, bz, ...], m. */
export interface TendonRoute {
  a: number;
  i: number;
  s: number[];
}

export interface FrameMsg {
  type: 'frame';
  scene: number;
  /** Steps since the scene was created. */
  step: number;
  /** Simulated time, s. */
  t: number;
  /** World-from-link pose per link handle, for every link that can move. */
  links?: Record<string, Pose>;
  /** Node positions per soft actor handle, flat [x0, y0, z0, x1, ...], m. */
  soft?: Record<string, number[]>;
  contacts?: Contact[];
  /** The scene's constraints (optional). */
  constraints?: ConstraintMarker[];
  /** The spatial tendons' routes (optional). */
  tendons?: TendonRoute[];
  /** Joint state per actor handle (optional). */
  joints?: Record<string, JointState>;
  /** Named scalar or vector signals to plot (optional). */
  signals?: Record<string, number | number[]>;
}

/** Replay only: every line of the file has been sent. */
export interface EndMsg {
  type: 'end';
  /** Number of `frame` lines in the file. */
  frames: number;
}

/** Kinds of signals seen for the first time in a scene (sent before the frame that has them). */
export interface SignalsMsg {
  type: 'signals';
  scene: number;
  /** Signal name -> "sensor", "actuator", "velocity", "effort", "contact" or "user". */
  kinds: Record<string, string>;
}

/** Live only: state of the stepping loop. */
export interface StatusMsg {
  type: 'status';
  state: 'playing' | 'paused';
  speed: 'realtime' | 'fast';
  /** Latest simulated time, s. */
  t: number;
  /** Steps taken by the latest stepped scene. */
  step: number;
}

export type ServerMsg =
  | SessionMsg
  | HeaderMsg
  | SceneMsg
  | ActorMsg
  | DestroyMsg
  | FrameMsg
  | EndMsg
  | SignalsMsg
  | StatusMsg;

export type ControlAction = 'pause' | 'play' | 'fast' | 'step' | 'restore';

/** Page-to-server message. */
export interface ControlMsg {
  type: 'control';
  action: ControlAction;
}
