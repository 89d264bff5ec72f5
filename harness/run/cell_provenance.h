#pragma once
// The provenance of a cell's row (output/provenance.h says what each part is): made for every
// cell before anything is measured, so that a run reuses exactly the rows whose every part is
// what this build and these inputs give, and says why it measures the others again.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "config/config.h"
#include "gl/shader_library.h"
#include "output/provenance.h"
#include "output/result_store.h"
#include "run/cells.h"

namespace rl {

// The parts that are one for a whole run (or one per scene or technique), made once.
struct ProvenanceContext {
  std::string truth_code, metrics_code, draw_code, renderer, cost_model;
  std::map<std::string, std::string> inputs;          // by scene name
  std::map<std::string, std::string> technique_code;  // by technique; "" when unknown
};

// `renderer` names the GL renderer, its version and the timing method (GlContext's).
ProvenanceContext provenance_context(const SweepConfig& config, const std::string& renderer);

// The provenance of `cell` drawn with programs whose digest is `programs` (programs_digest()).
Provenance cell_provenance(const ProvenanceContext& context, const SweepConfig& config,
                           const Cell& cell, const std::string& programs);

// The programs a row was drawn with, as the store keeps them (JSON text), and back; the digest
// of a set of them as the shaders embedded now compose them ("" when one no longer composes:
// a file it includes is gone, or the text is not such a list).
std::string programs_text(const std::map<std::string, ProgramDesc>& programs);
std::vector<ProgramDesc> parse_programs(const std::string& text);
std::string programs_digest(const std::vector<ProgramDesc>& programs);

// Why a row measured from `stored` cannot stand for a cell whose provenance is `now`: one
// phrase per part that differs ("the programs of technique relief changed"), empty when none
// does. A part this build cannot know (an unidentifiable technique's code) never matches.
std::vector<std::string> provenance_changes(const Provenance& stored, const Provenance& now,
                                            const Cell& cell, const SweepConfig& config);

// The GL renderer this process draws with, its version and how it times frames: the renderer
// part of every row's provenance (makes the shared GL context).
std::string renderer_identity();

// Which stored rows a run reuses: of `usable` (the keys whose stored rows are whole and name
// their cells), those whose provenance is the cell's now; the others are measured again, and
// `reasons` says why, each phrase with how many cells it applies to, most first. A row stored
// under no cell's key whose identity (technique, scene, view, sizes, parameters) is a cell's is
// that cell measured before its key changed (a file's bytes, a scene's or the sweep's setting):
// `replaces` names it, and the new row takes its place.
struct ReusePlan {
  std::set<std::string> reuse;
  std::map<std::string, std::string> replaces;  // cell key -> the older key of its row
  size_t stale = 0;
  std::vector<std::pair<std::string, size_t>> reasons;
  // "288 rows reused; 12 re-measured: the programs of technique relief changed (12)".
  std::string summary() const;
};
ReusePlan plan_reuse(const SweepConfig& config, const std::vector<Cell>& cells,
                     const ResultStore& store, const std::set<std::string>& usable,
                     const ProvenanceContext& context);

}  // namespace rl
