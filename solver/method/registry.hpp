// The method registry: the one place that builds a run from a case and a spacing. A case names its
// method in "method" (default "sph") and may list others it supports in "methods"; `sandcastle run
// --method NAME` picks one of those. Adding a method is one entry in registry.cpp
// (docs/architecture.md, "Adding a method").
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "method/method.hpp"

namespace sc {

/// The names of the methods this build knows, in registry order.
std::vector<std::string> method_names();

/// Throws InputError (the case file, JSON path /method or /methods/NAME, the rule) if the case
/// names a method this build does not know, or if a method it supports rejects its parameters
/// ("methods"/NAME, e.g. an unknown key) or its scene. Allocates nothing.
void check_method(const CaseSpec& spec);

/// The case run with method `name` instead of its own: `name` must be the case's method or one
/// of its "methods" (InputError naming the case file, /methods and the flag otherwise). An empty
/// name keeps the case's method.
CaseSpec with_method(CaseSpec spec, const std::string& name);

/// Throws InputError (the case file, the JSON path of the feature, the rule) when the case has
/// something the domain decomposition over MPI ranks does not run yet: a method other than SPH.
/// Allocates nothing.
void check_decomposable(const CaseSpec& spec);

/// Whether method `name` writes checkpoints that resume bitwise (Method::writes_checkpoints).
bool method_writes_checkpoints(const std::string& name);

/// The case's method at t = 0 at spacing dx (check_method first). `decompose`: the scene is
/// decomposed over the MPI ranks of the run, every rank calling this with the same case (SPH only;
/// InputError naming the method otherwise, before anything is allocated).
template <int D>
std::unique_ptr<Method<D>> make_method(const CaseSpec& spec, double dx, bool decompose = false);

/// The case's method continuing from the checkpoint file `path`, which must come from the same
/// case (parameters hash) and spacing; `run` receives the runner's bookkeeping stored with it.
/// Throws InputError if the method writes no checkpoints or the file is unreadable or foreign.
/// `decompose` as for make_method: a checkpoint written by any number of ranks resumes on any number.
template <int D>
std::unique_ptr<Method<D>> resume_method(const CaseSpec& spec, double dx, const std::string& path, json& run,
                                         bool decompose = false);

}  // namespace sc
