// Reads an OpenSBP file with FabMo-Engine's own parser, as its engine reads a job
// (parser.parseFile: a stream, line by line), for the side-by-side figures in
// docs/performance.md. usage: node fabmo_parse.js FABMO_ENGINE_DIR FILE
// FabMo's runtime/opensbp/parser.js requires ../../log: a checkout whose log.js needs
// packages not installed can be given a stub (fabmo_side_by_side.py writes one).
const path = require("path");
const parser = require(path.resolve(process.argv[2], "runtime/opensbp/parser.js"));
parser.parseFile(process.argv[3], (err, statements) => {
  if (err) {
    console.error(err.message);
    process.exit(1);
  }
  console.log(`${statements.length} statements`);
});
