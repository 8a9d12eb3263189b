// A project scene in MuJoCo 3.14's WebAssembly module: its files copied into the module's in-memory
// file system at the paths they have on disk (so that MuJoCo resolves every relative <include>,
// meshdir and file itself), the object's collision replaced by one configuration (an MJCF edit,
// docs/mujoco3.md, "The configurations"), the names of the compiled model, and the pairs config's
// "grasp" section.
import { existsSync, readFileSync, statSync } from "node:fs";
import path from "node:path";
import { XMLBuilder, XMLParser } from "fast-xml-parser";

// The configurations: what collides the object in 3.14.
//   hull   the scene unchanged: the mesh geom, which 3.14 collides as its convex hull (multiccd
//          on, 3.14's default)
//   sdf    the object's mesh geom turned into <geom type="sdf" mesh=...>: 3.14 builds an octree
//          of the mesh's signed distance at compile time and finds contacts by gradient descent
//          from sdf_initpoints starts (default 40)
//   sdf10  the same with <option sdf_initpoints="10"/>
//   flex   a rigid flex of the same mesh file in the object body (<flexcomp type="mesh"
//          rigid="true" radius=FLEX_RADIUS>), colliding as a non-convex triangle mesh inflated by
//          its radius; the mesh geom keeps its mass and inertia and no longer collides
export const CONFIGURATIONS = ["hull", "sdf", "sdf10", "flex"];
export const FLEX_RADIUS = 0.0005;  // m
export const SDF10_INITPOINTS = 10;

// A bad input of the runner's (a missing file, a bad pairs config): one line, exit code 2.
export class InputError extends Error {}

const XML_OPTIONS = {
  preserveOrder: true,
  ignoreAttributes: false,
  attributeNamePrefix: "",
  parseAttributeValue: false,
  parseTagValue: false,
  trimValues: true,
  commentPropName: "#comment",
};

function parseXml(file) {
  let text;
  try {
    text = readFileSync(file, "utf8");
  } catch (e) {
    throw new InputError(`${file}: cannot read the scene (${e.code || e.message})`);
  }
  try {
    return new XMLParser(XML_OPTIONS).parse(text);
  } catch (e) {
    throw new InputError(`${file}: not XML (${String(e.message).split("\n")[0]})`);
  }
}

// The element nodes of a parsed document (fast-xml-parser's ordered form: [{tag: [children],
// ":@": {attributes}}]), depth first, each with its tag and attributes.
function tagOf(node) {
  return Object.keys(node).find((k) => k !== ":@" && !k.startsWith("#"));
}
function* elements(nodes) {
  for (const node of nodes) {
    const tag = tagOf(node);
    if (tag === undefined) continue;
    if (!node[":@"]) node[":@"] = {};
    yield { tag, node, attributes: node[":@"], children: node[tag] };
    yield* elements(node[tag]);
  }
}

// Every file the scene reads: the scene, its includes (recursively) and each `file` attribute
// resolved against the scene's folder and the including file's folder, each with and without every
// meshdir, texturedir and assetdir the scene names. A candidate that does not exist is skipped
// (MuJoCo reports the one it misses); copying a few files MuJoCo does not read costs nothing.
export function sceneFiles(scene) {
  const files = new Set([scene]);
  const dirs = new Set();
  const sceneDir = path.dirname(scene);
  const visit = (file) => {
    const refs = [];
    for (const e of elements(parseXml(file))) {
      if (e.tag === "compiler") {
        for (const key of ["meshdir", "texturedir", "assetdir"]) {
          if (e.attributes[key] !== undefined) dirs.add(e.attributes[key]);
        }
      }
      if (e.attributes.file !== undefined) refs.push([e.tag, e.attributes.file]);
    }
    for (const [tag, ref] of refs) {
      for (const base of new Set([sceneDir, path.dirname(file)])) {
        const candidates = [path.resolve(base, ref)];
        if (tag !== "include") for (const d of dirs) candidates.push(path.resolve(base, d, ref));
        for (const c of candidates) {
          if (files.has(c) || !existsSync(c) || !statSync(c).isFile()) continue;
          files.add(c);
          if (tag === "include") visit(c);
        }
      }
    }
  };
  visit(scene);
  // A meshdir named in an include read after a mesh's element: one more pass finds its files.
  for (const f of [...files]) if (f.endsWith(".xml")) visit(f);
  return [...files];
}

// Copies `files` into the module's file system at their own absolute paths.
export function mountFiles(mj, files) {
  for (const f of files) {
    mj.FS.mkdirTree(path.dirname(f));
    mj.FS.writeFile(f, readFileSync(f));
  }
}

// The text of a name or path buffer at `adr`. mj_id2name of the 3.14.0 bindings returns junk
// ("emsc") for an unnamed element, so names are read from m.names directly.
function bufferText(buffer, adr) {
  const bytes = new Uint8Array(buffer.buffer, buffer.byteOffset, buffer.length);
  let end = adr;
  while (end < bytes.length && bytes[end] !== 0) end++;
  return new TextDecoder().decode(bytes.subarray(adr, end));
}

// The names of a compiled model's bodies, geoms and actuators ("" when unnamed).
export function modelNames(m) {
  const read = (n, adr) => Array.from({ length: n }, (_, i) => bufferText(m.names, adr[i]));
  return {
    body: read(m.nbody, m.name_bodyadr),
    geom: read(m.ngeom, m.name_geomadr),
    actuator: read(m.nu, m.name_actuatoradr),
    mesh: read(m.nmesh, m.name_meshadr),
  };
}

// The object's geoms: those of the object body's tree (as graspcd's run finds them).
export function objectGeoms(m, objectBody) {
  const out = [];
  for (let g = 0; g < m.ngeom; g++) if (m.body_rootid[m.geom_bodyid[g]] === objectBody) out.push(g);
  return out;
}

// --- The configuration's MJCF edit --------------------------------------------------------------

// Quaternions (w, x, y, z), as MuJoCo's mju_mulQuat and mju_rotVecQuat.
function mulQuat(a, b) {
  return [
    a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
    a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
    a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
  ];
}
function rotate(q, v) {
  const r = mulQuat(mulQuat(q, [0, v[0], v[1], v[2]]), [q[0], -q[1], -q[2], -q[3]]);
  return [r[1], r[2], r[3]];
}
const num = (x) => String(x);

// The edit of one configuration, applied to the main scene file's document. `unmodified` is the
// scene as 3.14 compiles it unchanged (the object geom's compiled pose, mesh and collision
// parameters; needed by "flex" only). Returns the edited XML text and the inflation (m).
export function editScene(sceneFile, configuration, objectBodyName, unmodified) {
  const doc = parseXml(sceneFile);
  const all = [...elements(doc)];
  const root = all.find((e) => e.tag === "mujoco");
  if (!root) throw new InputError(`${sceneFile}: no <mujoco> element`);
  if (configuration === "hull") return { xml: null, inflation: 0 };

  const body = all.find((e) => e.tag === "body" && e.attributes.name === objectBodyName);
  if (!body) {
    throw new InputError(
      `${sceneFile}: the object body '${objectBodyName}' is not in this file (the runner edits the scene's own file)`,
    );
  }
  const meshGeoms = [...elements(body.children)].filter(
    (e) => e.tag === "geom" && e.attributes.mesh !== undefined && (e.attributes.type || "mesh") === "mesh",
  );
  if (meshGeoms.length !== 1) {
    throw new InputError(
      `${sceneFile}: the object body '${objectBodyName}' has ${meshGeoms.length} mesh geoms; the runner replaces exactly one`,
    );
  }
  const geom = meshGeoms[0];
  let inflation = 0;
  if (configuration === "sdf" || configuration === "sdf10") {
    geom.attributes.type = "sdf";
    if (configuration === "sdf10") {
      root.children.push({ option: [], ":@": { sdf_initpoints: num(SDF10_INITPOINTS) } });
    }
  } else if (configuration === "flex") {
    const u = unmodified;
    const g = u.objectMeshGeom;
    const mesh = u.m.geom_dataid[g];
    // The mesh file's coordinates, scaled, in the body frame: the compiled geom's pose is the
    // XML geom's pose times the mesh's own (3.14 centres and aligns a mesh: mesh_pos, mesh_quat),
    // so the XML pose is the compiled one times the mesh's inverse. flexcomp scales its points
    // first, then applies pos and quat.
    const gq = Array.from(u.m.geom_quat.subarray(4 * g, 4 * g + 4));
    const gp = Array.from(u.m.geom_pos.subarray(3 * g, 3 * g + 3));
    const mq = Array.from(u.m.mesh_quat.subarray(4 * mesh, 4 * mesh + 4));
    const mp = Array.from(u.m.mesh_pos.subarray(3 * mesh, 3 * mesh + 3));
    const q = mulQuat(gq, [mq[0], -mq[1], -mq[2], -mq[3]]);
    const shift = rotate(q, mp);
    const p = [gp[0] - shift[0], gp[1] - shift[1], gp[2] - shift[2]];
    const scale = Array.from(u.m.mesh_scale.subarray(3 * mesh, 3 * mesh + 3));
    const file = bufferText(u.m.paths, u.m.mesh_pathadr[mesh]);
    const at = (array, n) => Array.from(array.subarray(n * g, n * g + n)).map(num).join(" ");
    geom.attributes.contype = "0";
    geom.attributes.conaffinity = "0";
    const contact = {
      contype: num(u.m.geom_contype[g]),
      conaffinity: num(u.m.geom_conaffinity[g]),
      condim: num(u.m.geom_condim[g]),
      priority: num(u.m.geom_priority[g]),
      friction: at(u.m.geom_friction, 3),
      solmix: num(u.m.geom_solmix[g]),
      solref: at(u.m.geom_solref, 2),
      solimp: at(u.m.geom_solimp, 5),
      margin: num(u.m.geom_margin[g]),
      gap: num(u.m.geom_gap[g]),
      selfcollide: "none",
      internal: "false",
    };
    body.children.push({
      flexcomp: [{ contact: [], ":@": contact }],
      ":@": {
        name: `${objectBodyName}_flex`,
        type: "mesh",
        dim: "2",
        file,
        scale: scale.map(num).join(" "),
        pos: p.map(num).join(" "),
        quat: q.map(num).join(" "),
        rigid: "true",
        radius: num(FLEX_RADIUS),
      },
    });
    inflation = FLEX_RADIUS;
  } else {
    throw new InputError(`unknown configuration '${configuration}' (${CONFIGURATIONS.join(", ")})`);
  }
  const xml = new XMLBuilder({ ...XML_OPTIONS, format: true, suppressEmptyNode: true }).build(doc);
  return { xml, inflation };
}

// --- The pairs config's "grasp" section ---------------------------------------------------------

// The "grasp" section of SCENE.pairs.json (src/graspcd/grasp/drive_config.h), checked as graspcd
// checks it; a config without one is bad input here (the node runner drives only such scenes).
export function loadDrive(configPath) {
  let text;
  try {
    text = readFileSync(configPath, "utf8");
  } catch (e) {
    throw new InputError(`${configPath}: cannot open the pair config (${e.code || e.message})`);
  }
  let j;
  try {
    j = JSON.parse(text);
  } catch (e) {
    throw new InputError(`${configPath}: not JSON (${e.message})`);
  }
  const bad = (what) => new InputError(`${configPath}: 'grasp': ${what}`);
  if (!j || typeof j !== "object" || !("grasp" in j)) {
    throw new InputError(
      `${configPath}: no "grasp" section: the node runner drives a hand through its own actuators (scenes of the project's hands run on graspcd's C++ controllers)`,
    );
  }
  const g = j.grasp;
  const text_ = (v, name) => {
    if (typeof v !== "string" || v === "") throw bad(`'${name}' must be a non-empty string`);
    return v;
  };
  const number = (v, name) => {
    if (typeof v !== "number" || !Number.isFinite(v)) throw bad(`'${name}' must be a number`);
    return v;
  };
  if (!g || typeof g !== "object" || Array.isArray(g)) throw bad("must be an object");
  const drive = { object: "object", hand: "", support: "", close: [], lift: null };
  for (const [field, value] of Object.entries(g)) {
    if (field === "object" || field === "hand" || field === "support") {
      drive[field] = text_(value, field);
    } else if (field === "close") {
      if (!Array.isArray(value) || value.length === 0) throw bad("'close' must be a non-empty array");
      for (const c of value) {
        if (!c || typeof c !== "object") throw bad("each entry of 'close' must be an object");
        const cd = { actuator: "", step: 0, squeeze: 0, touch: [] };
        for (const [f, v] of Object.entries(c)) {
          if (f === "actuator") cd.actuator = text_(v, f);
          else if (f === "step") {
            cd.step = number(v, f);
            if (!(cd.step > 0)) throw bad("'step' must be > 0");
          } else if (f === "squeeze") cd.squeeze = number(v, f);
          else if (f === "touch") {
            if (!Array.isArray(v) || v.length === 0) throw bad("'touch' must be a non-empty array");
            cd.touch = v.map((t) => text_(t, "touch"));
          } else throw bad(`unknown field '${f}' in 'close'`);
        }
        if (!cd.actuator || !(cd.step > 0) || cd.touch.length === 0) {
          throw bad("each entry of 'close' needs 'actuator', 'step' and 'touch'");
        }
        drive.close.push(cd);
      }
    } else if (field === "lift") {
      if (!value || typeof value !== "object" || Object.keys(value).sort().join() !== "actuator,by") {
        throw bad(`'lift' must be {"actuator": NAME, "by": CTRL}`);
      }
      drive.lift = { actuator: text_(value.actuator, "actuator"), by: number(value.by, "by") };
    } else {
      throw bad(`unknown field '${field}'`);
    }
  }
  if (!drive.hand || drive.close.length === 0 || !drive.lift) throw bad("needs 'hand', 'close' and 'lift'");
  return drive;
}

// graspcd's glob ('*' only) and its patterns: "geom:GLOB", "body:GLOB" or "GLOB" (either name),
// over the collidable geoms (contype or conaffinity non-zero), in id order
// (src/graspcd/mujoco/geom_trees.h, match_geoms).
export function globMatch(pattern, name) {
  let p = 0, n = 0, star = -1, mark = 0;
  while (n < name.length) {
    if (p < pattern.length && pattern[p] === "*") {
      star = p++;
      mark = n;
    } else if (p < pattern.length && pattern[p] === name[n]) {
      p++;
      n++;
    } else if (star >= 0) {
      p = star + 1;
      n = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.length && pattern[p] === "*") p++;
  return p === pattern.length;
}

export function matchGeoms(m, names, pattern) {
  let byGeom = true, byBody = true, glob = pattern;
  if (glob.startsWith("geom:")) {
    byBody = false;
    glob = glob.slice(5);
  } else if (glob.startsWith("body:")) {
    byGeom = false;
    glob = glob.slice(5);
  }
  const out = [];
  for (let g = 0; g < m.ngeom; g++) {
    const hit =
      (byGeom && globMatch(glob, names.geom[g])) || (byBody && globMatch(glob, names.body[m.geom_bodyid[g]]));
    if (hit && (m.geom_contype[g] !== 0 || m.geom_conaffinity[g] !== 0)) out.push(g);
  }
  return out;
}
