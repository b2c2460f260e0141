// Validates a .glb with the Khronos glTF validator and checks rbsim's animation layout.
// Usage: node validate_glb.mjs FILE.glb EXPECTED_KEYS EXPECTED_NODES
// Exit 0 when the validator reports no errors (warnings are printed), every animation sampler
// has EXPECTED_KEYS keys, and the scene has EXPECTED_NODES body nodes each with a translation and
// a rotation channel.
import { readFileSync } from "node:fs";
import validator from "gltf-validator";

const [file, keysArg, nodesArg] = process.argv.slice(2);
const bytes = new Uint8Array(readFileSync(file));
const report = await validator.validateBytes(bytes, { maxIssues: 100 });
const issues = report.issues;
for (const m of issues.messages) {
  const level = ["error", "warning", "info", "hint"][m.severity] ?? m.severity;
  console.log(`${level}: ${m.code} ${m.pointer ?? ""}: ${m.message}`);
}
console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos ` +
            `(validator ${report.validatorVersion})`);
let failed = issues.numErrors > 0;

// The JSON chunk: 12-byte header, then chunk length, type, text.
const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
const jsonLength = view.getUint32(12, true);
const doc = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
const expectedKeys = Number(keysArg);
const expectedNodes = Number(nodesArg);
const anim = doc.animations?.[0];
if (!anim) {
  console.log("FAIL: no animation");
  failed = true;
} else {
  for (const [i, s] of anim.samplers.entries()) {
    const inCount = doc.accessors[s.input].count, outCount = doc.accessors[s.output].count;
    if (inCount !== expectedKeys || outCount !== expectedKeys) {
      console.log(`FAIL: sampler ${i} has ${inCount} times and ${outCount} values, expected ${expectedKeys}`);
      failed = true;
    }
  }
  const paths = new Map();
  for (const c of anim.channels) paths.set(c.target.node, [...(paths.get(c.target.node) ?? []), c.target.path]);
  const animated = [...paths.values()].filter((p) => p.includes("translation") && p.includes("rotation")).length;
  if (animated !== expectedNodes) {
    console.log(`FAIL: ${animated} nodes have translation and rotation channels, expected ${expectedNodes}`);
    failed = true;
  }
}
console.log(failed ? "FAIL" : "OK");
process.exit(failed ? 1 : 0);
