#pragma once
// The members of a big scene file's runs (json_split.h) read straight into records, on any
// core: RapidJSON's reader, one member at a time, drives a handler that collects each
// member's flat fields (member_fields.h), from which the sphere or material is made. No JSON
// value is built and the run's text is not copied: RapidJSON parses it in place.
//
// It refuses, without a message, whatever the one-piece reading refuses and anything shaped
// otherwise than a scene member: the caller then reads the whole file in one piece, which
// says what is wrong and where.

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene_file/json_split.h"
#include "core/scene_file/sphere_json.h"
#include "materials/material.h"

namespace rtiow {

// A material as read, with its name (a view into the window, as a sphere's material name).
struct MaterialRecord {
  std::string_view name;
  Material material;
};

// What runs read to, in document order, before the names are resolved.
struct RunRecords {
  std::vector<MaterialRecord> materials;
  std::vector<SphereRecord> spheres;
  std::vector<std::uint64_t> hashes;  // NameIndex::hash of each member's name
};

// Reads the members of `run` (of "materials" or of "spheres"), which lies in `window`, into
// `records`; false unless the run is exactly the members the scan counted, each valid. The
// window's text is parsed in place (strings are decoded where they lie), and the records' names
// are views into it: keep it until they are resolved.
bool read_run_records(std::string& window, const MemberRun& run, RunRecords& records);

}  // namespace rtiow
