// Validates glTF 2.0 files (.glb or .gltf) with Khronos' validator, the npm package
// `gltf-validator` that scripts/fetch_gltf_validator.sh installs into tests/data/gltf-validator/,
// and prints each file's report as one line of JSON (the validator's own report object, every
// issue listed). Exits 2 when the validator cannot read a file at all (not glTF or GLB).
// Usage: node scripts/validate_gltf.mjs FILE...   (GLTF_VALIDATOR=DIR names another install)
import { readFile } from "node:fs/promises";
import { basename, dirname, join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const dir = process.env.GLTF_VALIDATOR || join(root, "tests/data/gltf-validator/node_modules/gltf-validator");
const validator = await import(pathToFileURL(join(dir, "module.mjs")).href);

if (process.argv.length < 3) {
    console.error("usage: node scripts/validate_gltf.mjs FILE...");
    process.exit(64);
}
for (const file of process.argv.slice(2)) {
    const bytes = new Uint8Array(await readFile(file));
    try {
        const report = await validator.validateBytes(bytes, {
            uri: basename(file),
            maxIssues: 0,
            writeTimestamp: false,
        });
        console.log(JSON.stringify(report));
    } catch (error) {
        console.error(`${file}: the validator could not read it: ${error}`);
        process.exit(2);
    }
}
