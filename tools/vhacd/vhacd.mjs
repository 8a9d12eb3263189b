// graspcd decompose --engine vhacd: V-HACD 4 (K. Mamou, "Volumetric hierarchical approximate
// convex decomposition", Game Engine Gems 3, 2016; github.com/kmammou/v-hacd) compiled to
// WebAssembly by the npm package vhacd-js, run by node.
//
//   node vhacd.mjs IN.json OUT.json
//
// IN.json: {"positions": [x, y, z, ...], "indices": [i, j, k, ...], "options": {...}}, the options
// as vhacd-js names them (maxHulls, voxelResolution, minVolumePercentError, maxRecursionDepth,
// shrinkWrap, fillMode, maxVerticesPerHull, minEdgeLength, findBestPlane). OUT.json: {"hulls":
// [{"positions": [...], "indices": [...]}, ...]}. Any failure: a message on stderr, exit code 1.
import { readFileSync, writeFileSync } from "node:fs";
import { ConvexMeshDecomposition } from "vhacd-js/lib/vhacd.js";

async function main(argv) {
  if (argv.length !== 2) {
    process.stderr.write("usage: node vhacd.mjs IN.json OUT.json\n");
    return 2;
  }
  const input = JSON.parse(readFileSync(argv[0], "utf8"));
  const mesh = {
    positions: Float64Array.from(input.positions),
    indices: Uint32Array.from(input.indices),
  };
  const decomposer = await ConvexMeshDecomposition.create();
  const hulls = decomposer.computeConvexHulls(mesh, { ...input.options, messages: "none" });
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
    process.stderr.write(`vhacd.mjs: ${err && err.message ? err.message : err}\n`);
    process.exit(1);
  },
);
