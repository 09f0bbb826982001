// A pipeline composed by name at run time: stage lists of the registry's
// kinds (stage_registry.hpp) with their options, under rules given by
// name (the first rows of the settings table, adapt_settings.hpp). The
// command (`metrica pipeline`) and Python's Pipeline both run theirs
// here: in the log-Euclidean space with filtered predicates, off a model,
// serial or speculative (what examples/compose does in C++, without a
// compiler).
#pragma once

#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/adapt_settings.hpp>
#include <metrica/pipeline/stage_registry.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace metrica {

// A stage: its name (its report key and epoch), its operation (a kind of
// the registry) and the values of its options.
struct StageSpec {
  std::string name, op;
  StageValues values;
};

struct ComposedPipeline {
  std::vector<StageSpec> cycle, polish, repair;
  PipelineRules rules;
};

// A kind of stage as help texts and value readers see it: its operation,
// what it does and its options (the registry's, without the Stage it
// makes: compiled once, here).
struct StageKindInfo {
  std::string_view op, help;
  std::vector<StageOption> options;
};
const std::vector<StageKindInfo>& stage_kind_infos();
// The kind `op`; InputError naming the kinds when there is none.
const StageKindInfo& stage_kind_info(std::string_view op, std::string_view stage);

// A stage list as the command writes it: stages separated by commas, each
// `[NAME=]OP[:OPTION=VALUE]...`; a value is true, false, a number or a
// name. "collapse,split,delaunay=flip:criterion=metric-delaunay,smooth:below=0.3".
// The name defaults to the operation's. InputError naming `list` (the
// option's spelling) for an empty stage or a malformed option.
std::vector<StageSpec> parse_stage_list(std::string_view text, std::string_view list);

// Every stage's operation and options checked (kinds, ranges, names once
// in a list) before anything runs: InputError naming the stage.
void check_composed(const ComposedPipeline& p);

// Runs `p` on `mesh`, whose metric is assigned; new and moved vertices
// take inputs.metric or inputs.background as in adapt, and with neither,
// the mesh's field as given (a background on the input mesh, whose field
// the adapted mesh's metric is in at the end). inputs.model must be none.
// `concurrency`: serial or speculative.
AdaptReport run_composed(Mesh& mesh, const ComposedPipeline& p, const AdaptInputs& inputs,
                         std::string_view concurrency);

}  // namespace metrica
