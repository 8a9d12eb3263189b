// graspcd decompose --engine vhacd: V-HACD 4 (K. Mamou, "Volumetric hierarchical approximate
// convex decomposition", Game Engine Gems 3, 2016; github.com/kmammou/v-hacd) compiled to
// WebAssembly by the npm package vhacd-js, run by node.
//
//   node vhacd.mjs IN.json OUT.json
//
// IN.json: {"positions": [x, y, z, ...], "indices": [i, j, k, ...], "options": {...}}, the options
// as vhacd-js names them (maxHulls, voxelResolution, minVolumePercentError, maxRecursionDepth,
// shrinkWrap, fillMode, maxVerticesPerHull, minEdgeLength, findBestPlane). OUT.json: {"hulls":
// [{"positions": [...], "indices": [...]}, ...]}. Any failure: one line "vhacd.mjs: WHAT" on
// stderr, in words graspcd passes on to its user (never node's stack or version banner), and
// exit code 1.
import { readFileSync, writeFileSync } from "node:fs";

// The first line of an error's message.
function firstLine(err) {
  const text = String(err && err.message !== undefined ? err.message : err);
  return text.split("\n")[0];
}

// What V-HACD's WebAssembly code (Emscripten's runtime) threw, said plainly: its heap stops at
// 2 GiB, and an abort or a trap inside it is its own failure, not the mesh file's.
function explain(err) {
  const text = firstLine(err);
  const wasm = err instanceof WebAssembly.RuntimeError || /^Aborted\(/.test(text);
  if (/OOM|enlarge memory|out of memory/i.test(text)) {
    return `V-HACD ran out of memory (its WebAssembly heap stops at 2 GiB): lower --resolution (${text})`;
  }
  if (wasm) return `V-HACD stopped inside its WebAssembly code: try another --resolution (${text})`;
  return text;
}

async function main(argv) {
  if (argv.length !== 2) {
    process.stderr.write("vhacd.mjs: usage: node vhacd.mjs IN.json OUT.json\n");
    return 2;
  }
  let ConvexMeshDecomposition;
  try {
    ({ ConvexMeshDecomposition } = await import("vhacd-js/lib/vhacd.js"));
  } catch (err) {
    throw new Error(
      `node could not load the vhacd-js package (${err && err.name ? err.name + ": " : ""}${firstLine(err)}): run ./run build (npm ci in tools/vhacd)`,
    );
  }
  const input = JSON.parse(readFileSync(argv[0], "utf8"));
  const mesh = {
    positions: Float64Array.from(input.positions),
    indices: Uint32Array.from(input.indices),
  };
  let hulls;
  try {
    const decomposer = await ConvexMeshDecomposition.create();
    hulls = decomposer.computeConvexHulls(mesh, { ...input.options, messages: "none" });
  } catch (err) {
    throw new Error(explain(err));
  }
  const out = hulls.map((h) => ({
    positions: Array.from(h.positions),
    indices: Array.from(h.indices),
  }));
  writeFileSync(argv[1], JSON.stringify({ hulls: out }));
  return 0;
}

main(process.argv.slice(2)).then(
  (code) => process.exit(code),
  (err) => {
    process.stderr.write(`vhacd.mjs: ${firstLine(err)}\n`);
    process.exit(1);
  },
);
