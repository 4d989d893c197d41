// Keyword arguments read as the command line's flags: `key_frames=7` is `--key-frames 7`,
// `whole_mesh=True` is `--whole-mesh`, `no_rollback=True` is `--no-rollback`. One definition of each
// option's name, default and check serves both; an unknown name or a value out of range is a
// ValueError with the command line's message.
#pragma once

#include <pybind11/pybind11.h>

#include <CLI/CLI.hpp>

namespace posekit::python {

/// Parses `keywords` with the options registered on `app` (which must not have required ones).
void parse_keywords(CLI::App& app, const pybind11::kwargs& keywords);

}  // namespace posekit::python
