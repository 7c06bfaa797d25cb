// SPDX-License-Identifier: MIT
// Runs the Khronos glTF-Validator (npm gltf-validator) on .glb files and fails on any error or
// warning: `node web/tools/validate-glb.mjs OUT.glb [MORE.glb ...]`. Prints each file's counts and
// its issues; infos and hints are printed but allowed. Exit status: 0 clean, 1 issues, 2 usage or a
// file or the validator that cannot be loaded (so a CTest running this fails rather than skips).
import { readFile } from 'node:fs/promises';
import { basename } from 'node:path';

// Warnings we accept, each with the reason. None so far: odeskin's exports must be warning-free.
const allowedWarnings = new Map([]);

const severities = ['error', 'warning', 'info', 'hint'];

async function loadValidator() {
  try {
    return (await import('gltf-validator')).default;
  } catch (error) {
    console.error(`validate-glb: cannot load the gltf-validator package (run scripts/install-deps.sh): ${error.message}`);
    process.exit(2);
  }
}

async function validateFile(validator, path) {
  let bytes;
  try {
    bytes = new Uint8Array(await readFile(path));
  } catch (error) {
    console.error(`validate-glb: ${path}: cannot read: ${error.message}`);
    return false;
  }
  const report = await validator.validateBytes(bytes, { uri: basename(path), maxIssues: 0 });
  const { numErrors, numWarnings, numInfos, numHints, messages } = report.issues;
  const blocking = messages.filter(
    (m) => m.severity === 0 || (m.severity === 1 && !allowedWarnings.has(m.code)));
  console.log(`${path}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints` +
              ` (${report.info?.generator ?? 'unknown generator'}, ${report.info?.drawCallCount ?? 0} draw calls,` +
              ` ${report.info?.animationCount ?? 0} animations, ${report.info?.maxAttributes ?? 0} max attributes)`);
  for (const m of messages) {
    const tag = severities[m.severity] ?? `severity ${m.severity}`;
    const allowed = m.severity === 1 && allowedWarnings.has(m.code) ? ` (allowed: ${allowedWarnings.get(m.code)})` : '';
    console.log(`  ${tag} ${m.code}${m.pointer ? ' at ' + m.pointer : ''}: ${m.message}${allowed}`);
  }
  return blocking.length === 0;
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node web/tools/validate-glb.mjs FILE.glb [FILE.glb ...]');
  process.exit(2);
}
const validator = await loadValidator();
let ok = true;
for (const file of files) ok = (await validateFile(validator, file)) && ok;
process.exit(ok ? 0 : 1);
