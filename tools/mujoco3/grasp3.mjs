// graspcd's driven grasp in MuJoCo 3.14 (the official WebAssembly build, npm @mujoco/mujoco),
// written as a run record for `graspcd judge` (docs/mujoco3.md; the record: docs/run-record.md).
//
//   node tools/mujoco3/grasp3.mjs SCENE --configuration hull|sdf|sdf10|flex --out RECORD
//        [--noslip N] [--multiccd on|off] [--max-steps N] [--six-directions] [--no-contacts]
//        [--config PAIRS.json] [--summary] [--print-model]
//
// Exit codes: 0 the record was written to its end ("ok", or "nonfinite": the state went
// non-finite and the run stopped); 3 MuJoCo 3.14 cannot start the scene in this configuration
// (its compile refused it): the record is a header and {"end": {"status": "cannot start",
// "message": ...}}, and one line on stderr names the scene; 2 bad usage or input (a missing scene,
// a pairs config without a "grasp" section, a missing npm package): one line on stderr, no
// record; 1 anything else (a defect of the runner: its message on stderr).
import { existsSync, renameSync } from "node:fs";
import path from "node:path";
import { parseArgs } from "node:util";

const USAGE = `usage: node tools/mujoco3/grasp3.mjs SCENE --configuration hull|sdf|sdf10|flex --out RECORD
  [--noslip N] [--multiccd on|off] [--max-steps N] [--six-directions] [--no-contacts]
  [--config PAIRS.json] [--summary] [--print-model]

Runs graspcd's driven grasp (the pairs config's "grasp" section: close, squeeze, settle, lift,
hold) on SCENE in MuJoCo 3.14 (WebAssembly) with the object collided by one configuration, and
writes the run record RECORD (JSON Lines; docs/run-record.md) for graspcd judge.

  --configuration  hull: the scene unchanged (3.14 collides the mesh as its convex hull);
                   sdf: the object's mesh geom as a mesh SDF (type="sdf", sdf_initpoints 40);
                   sdf10: the same with sdf_initpoints 10; flex: a rigid flex of the object's
                   mesh (radius 0.5 mm) in its body, the mesh geom no longer colliding
  --noslip N       MuJoCo's noslip iterations (as graspcd grasp --noslip; default the scene's)
  --multiccd       on (3.14's default) or off
  --max-steps N    most closing grasp steps (default 400, as graspcd grasp)
  --six-directions after the hold, the six-direction test (docs/run-record.md)
  --no-contacts    state lines without the simulator's contacts
  --config FILE    the pairs config (default SCENE.pairs.json beside SCENE)
  --summary        one JSON line on stdout: first contacts, step cost, object rise, tilt, speeds
  --print-model    print the compiled model's bodies and geoms as JSON on stdout (no run)

Exit codes: 0 record written ("ok" or "nonfinite"), 3 cannot start (record written), 2 bad
usage or input (no record), 1 a defect of the runner.`;

class UsageError extends Error {}

function fail(code, message) {
  process.stderr.write(`${message}\n`);
  process.exit(code);
}

// Imports a module of the runner or of its npm packages; a package that is not installed is one
// line, exit code 2.
async function need(specifier) {
  try {
    return await import(specifier);
  } catch (e) {
    if (e && e.code === "ERR_MODULE_NOT_FOUND") {
      const folder = path.dirname(new URL(import.meta.url).pathname);
      fail(2, `grasp3.mjs: the npm packages of ${folder} (@mujoco/mujoco, fast-xml-parser) are not installed: run ./run build, or npm ci there (${e.message.split("\n")[0]})`);
    }
    throw e;
  }
}

async function loadModule() {
  const { default: loadMujoco } = await need("@mujoco/mujoco");
  return await loadMujoco();
}

function parse(argv) {
  let parsed;
  try {
    parsed = parseArgs({
      args: argv,
      allowPositionals: true,
      options: {
        configuration: { type: "string" },
        out: { type: "string" },
        noslip: { type: "string" },
        multiccd: { type: "string" },
        "max-steps": { type: "string" },
        "six-directions": { type: "boolean" },
        "no-contacts": { type: "boolean" },
        config: { type: "string" },
        summary: { type: "boolean" },
        "print-model": { type: "boolean" },
        help: { type: "boolean", short: "h" },
      },
    });
  } catch (e) {
    throw new UsageError(e.message);
  }
  const o = parsed.values;
  if (o.help) {
    process.stdout.write(USAGE + "\n");
    process.exit(0);
  }
  if (parsed.positionals.length !== 1) throw new UsageError("one SCENE is required");
  const integer = (text, name, min) => {
    if (text === undefined) return undefined;
    if (!/^[0-9]+$/.test(text) || Number(text) < min) throw new UsageError(`--${name} must be an integer >= ${min}`);
    return Number(text);
  };
  if (o.multiccd !== undefined && o.multiccd !== "on" && o.multiccd !== "off") {
    throw new UsageError("--multiccd must be on or off");
  }
  return {
    scene: parsed.positionals[0],
    configuration: o.configuration,
    out: o.out,
    noslip: integer(o.noslip, "noslip", 0),
    multiccd: o.multiccd === undefined ? undefined : o.multiccd === "on",
    maxSteps: integer(o["max-steps"], "max-steps", 1) ?? 400,
    sixDirections: Boolean(o["six-directions"]),
    contacts: !o["no-contacts"],
    config: o.config,
    summary: Boolean(o.summary),
    printModel: Boolean(o["print-model"]),
  };
}

async function main(argv) {
  const args = parse(argv);
  const scene = await need("./lib/scene.mjs");
  const { DrivenGrasp, NonFinite, SIX_DIRECTIONS } = await need("./lib/drive.mjs");
  const { RecordWriter } = await need("./lib/record.mjs");
  if (!scene.CONFIGURATIONS.includes(args.configuration)) {
    throw new UsageError(`--configuration must be one of ${scene.CONFIGURATIONS.join(", ")}`);
  }
  if (!args.out && !args.printModel) throw new UsageError("--out RECORD is required");
  if (args.out && args.printModel) throw new UsageError("--print-model writes no record: no --out");
  const scenePath = path.resolve(args.scene);
  if (!existsSync(scenePath)) throw new scene.InputError(`${args.scene}: cannot open the scene`);
  const configPath = args.config ?? scenePath.replace(/\.xml$/, "") + ".pairs.json";
  const drive = scene.loadDrive(configPath);
  const mj = await loadModule();
  scene.mountFiles(mj, scene.sceneFiles(scenePath));

  // The record: written to a hidden file beside RECORD, renamed into place at the end.
  const partial = args.out ? path.join(path.dirname(args.out), `.${path.basename(args.out)}.partial`) : null;
  const writer = args.out ? new RecordWriter(partial) : null;
  const header = {
    format: "graspcd-run",
    version: 1,
    scene: args.scene,
    simulator: `MuJoCo ${mj.mj_versionString()} (WebAssembly)`,
    configuration: args.configuration,
    timestep: null,
    nq: null,
    nv: null,
    object: drive.object,
    hand: drive.hand,
    support: drive.support || "world",
    contacts: args.contacts,
    inflation: args.configuration === "flex" ? scene.FLEX_RADIUS : 0,
    max_steps: args.maxSteps,
  };
  if (args.sixDirections) header.six_directions = { ...SIX_DIRECTIONS };
  const finish = (end, code) => {
    if (writer) {
      writer.line({ end });
      writer.close();
      renameSync(partial, args.out);
    }
    return code;
  };
  const cannotStart = (what, e) => {
    const message = String(e.message || e).replace(/\s+/g, " ").replace(/^Error: /, "").trim();
    if (writer) writer.line(header);
    process.stderr.write(`${args.scene}: MuJoCo ${mj.mj_versionString()} cannot start the ${args.configuration} configuration: ${what}: ${message}\n`);
    return finish({ status: "cannot start", message: `${what}: ${message}` }, 3);
  };

  // The unmodified scene as 3.14 compiles it: nq, nv and the geoms the record's ids refer to
  // (the scene as given), and what the flex edit copies from the object's mesh geom.
  let unmodified;
  try {
    unmodified = { m: mj.MjModel.from_xml_path(scenePath) };
  } catch (e) {
    return cannotStart("the scene does not compile", e);
  }
  const names0 = scene.modelNames(unmodified.m);
  header.timestep = unmodified.m.opt.timestep;
  header.nq = unmodified.m.nq;
  header.nv = unmodified.m.nv;
  // MuJoCo's options as the run sets them (as graspcd grasp --noslip does, on the compiled model).
  const multiccdBit = mj.mjtDisableBit.mjDSBL_MULTICCD.value;
  const setOptions = (model) => {
    if (args.noslip !== undefined) model.opt.noslip_iterations = args.noslip;
    if (args.multiccd !== undefined) {
      const flags = model.opt.disableflags;
      model.opt.disableflags = args.multiccd ? flags & ~multiccdBit : flags | multiccdBit;
    }
    header.noslip_iterations = model.opt.noslip_iterations;
    header.multiccd = (model.opt.disableflags & multiccdBit) === 0;
  };
  setOptions(unmodified.m);
  const objectBody = names0.body.indexOf(drive.object);
  if (objectBody < 0) throw new scene.InputError(`${configPath}: 'grasp': the scene has no body named '${drive.object}'`);
  unmodified.objectMeshGeom = scene
    .objectGeoms(unmodified.m, objectBody)
    .find((g) => unmodified.m.geom_type[g] === mj.mjtGeom.mjGEOM_MESH.value);

  // The configuration's edit, written over the scene's file in the module's file system (its
  // includes and meshes keep resolving from there).
  const { xml, inflation } = scene.editScene(scenePath, args.configuration, drive.object, unmodified);
  header.inflation = inflation;
  let m = unmodified.m;
  if (xml !== null) {
    mj.FS.writeFile(scenePath, xml);
    try {
      m = mj.MjModel.from_xml_path(scenePath);
    } catch (e) {
      unmodified.m.delete();
      return cannotStart(`the ${args.configuration} edit does not compile`, e);
    }
  }
  const names = scene.modelNames(m);
  // The geom ids of the scene as given: the edits keep every body and geom where it was (the
  // flex adds a flex, no geom), so the map is the identity; checked here, and against MuJoCo 2.2's
  // compile by tests/app/mujoco3_runner_test.cpp.
  if (m.ngeom !== unmodified.m.ngeom || m.nbody !== unmodified.m.nbody || m.nq !== header.nq || m.nv !== header.nv) {
    throw new Error(`${args.scene}: the ${args.configuration} edit changed the model's bodies, geoms or joints`);
  }
  for (let g = 0; g < m.ngeom; g++) {
    if (m.geom_bodyid[g] !== unmodified.m.geom_bodyid[g] || names.geom[g] !== names0.geom[g]) {
      throw new Error(`${args.scene}: the ${args.configuration} edit moved geom ${g}`);
    }
  }
  const geomMap = Array.from({ length: m.ngeom }, (_, g) => g);
  if (m !== unmodified.m) unmodified.m.delete();
  const objectFlexes = [];
  for (let f = 0; f < m.nflex; f++) {
    // A flex whose vertices all belong to the object body (m.flex_rigid, a byte array, throws a
    // BindingError in the 3.14.0 bindings: the vertices' bodies say the same).
    let all = true;
    for (let v = m.flex_vertadr[f]; v < m.flex_vertadr[f] + m.flex_vertnum[f]; v++) {
      all = all && m.flex_vertbodyid[v] === objectBody;
    }
    if (all) objectFlexes.push(f);
  }
  if (args.configuration === "flex" && objectFlexes.length !== 1) {
    throw new Error(`${args.scene}: the rigid flex is not the object body's`);
  }

  if (args.printModel) {
    const geomTypes = Object.fromEntries(
      Object.entries(mj.mjtGeom).filter(([k]) => k.startsWith("mjGEOM_")).map(([k, v]) => [v.value, k.slice(7).toLowerCase()]),
    );
    process.stdout.write(JSON.stringify({
      simulator: header.simulator,
      nq: m.nq,
      nv: m.nv,
      bodies: names.body.map((name, b) => ({ name, parent: m.body_parentid[b] })),
      geoms: names.geom.map((name, g) => ({
        name,
        body: m.geom_bodyid[g],
        type: geomTypes[m.geom_type[g]],
        id: geomMap[g],
      })),
      body_mass: Array.from(m.body_mass),
      flexes: objectFlexes.map((f) => ({ id: f, vertices: m.flex_vertnum[f], radius: m.flex_radius[f] })),
    }) + "\n");
    return 0;
  }

  setOptions(m);
  if (writer) writer.line(header);

  const d = new mj.MjData(m);
  if (m.nkey > 0) mj.mj_resetDataKeyframe(m, d, 0);
  mj.mj_forward(m, d);
  const run = new DrivenGrasp(mj, m, d, names, drive, {
    objectFlexes,
    geomMap,
    writer,
    contacts: args.contacts,
    config: configPath,
  });
  let end;
  try {
    end = { closing: run.run(args.maxSteps), status: "ok" };
    if (args.sixDirections) run.sixDirections();
  } catch (e) {
    if (!(e instanceof NonFinite)) throw e;
    end = { status: "nonfinite", message: e.message };
  }
  if (args.summary) {
    process.stdout.write(JSON.stringify({
      scene: args.scene,
      simulator: header.simulator,
      configuration: args.configuration,
      noslip_iterations: header.noslip_iterations,
      multiccd: header.multiccd,
      status: end.status,
      closing: end.closing ?? null,
      ...run.summary(),
    }) + "\n");
  }
  return finish(end, 0);
}

main(process.argv.slice(2)).then(
  (code) => process.exit(code),
  (e) => {
    if (e instanceof UsageError) fail(2, `grasp3.mjs: ${e.message}\n${USAGE}`);
    if (e && e.constructor && e.constructor.name === "InputError") fail(2, e.message);
    fail(1, `grasp3.mjs: ${e && e.stack ? e.stack : e}`);
  },
);
