#pragma once
/// @file sources.h
/// What a run was computed from, by content: the form files its kernels were compiled from
/// (recorded by the build, cpp/form_sources.cmake) and the input files it read (the mesh), each
/// by its SHA-256. A run writes them into scene.txt and its checkpoints; a replay (--scene) or a
/// restart from them refuses, in one line, an executable built from other forms or an input
/// file whose content has changed, instead of computing another answer without a word.

#include <map>
#include <string>

namespace gelx
{

/// path -> SHA-256 (hex)
using Sources = std::map<std::string, std::string>;

/// What this run has been computed from so far: the form files whose kernels this program was
/// built with (forms/NAME.py and the modules they may import, by their paths in the source
/// tree) and the input files it has read (record_input_file), by the path it read them at.
Sources run_sources();

/// Record the content of the input file at `path`, which the run reads, under `name` (what
/// the run's parameters call it). If the run replays a record (expect_sources) that holds
/// `name` with other content, throws InputError naming it.
void record_input_file(const std::string& path, const std::string& name);

/// Make `recorded`, the sources of the run being replayed or continued (`origin` names where
/// they were read), what this run must be computed from: a form file recorded with other
/// content than this program was built with, or not recorded where the record has forms, ends
/// the run here (InputError, one line); an input file is compared when record_input_file reads
/// it. A record without forms (one written before gelx recorded them) is not compared.
void expect_sources(const Sources& recorded, const std::string& origin,
                    const std::string& program);

} // namespace gelx
