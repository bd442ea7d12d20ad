// Converts an INRIA .ply capture to GaussianSplats3D's .ksplat with that project's own
// generator, for TestGaussianSplatFormats (the ksplat format has no other writer).
//   node ply-to-ksplat.mjs NODE_MODULES_DIR INPUT.ply OUTPUT.ksplat LEVEL SH_DEGREE
import * as fs from 'fs';
import * as path from 'path';
import { pathToFileURL } from 'url';

const [, , modules, input, output, level, degree] = process.argv;
const library = path.join(modules, '@mkkellogg/gaussian-splats-3d/build/gaussian-splats-3d.module.js');
const G = await import(pathToFileURL(library).href);
const data = fs.readFileSync(input);
const bytes = data.buffer.slice(data.byteOffset, data.byteOffset + data.byteLength);
const splats = G.PlyParser.parseToUncompressedSplatArray(bytes, parseInt(degree));
// No alpha threshold: every Gaussian is kept.
const generator = G.SplatBufferGenerator.getStandardGenerator(0, parseInt(level));
fs.writeFileSync(output, Buffer.from(generator.generateFromUncompressedSplatArray(splats).bufferData));
