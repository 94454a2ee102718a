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

/// Whether method `name` writes checkpoints that resume bitwise (Method::writes_checkpoints).
bool method_writes_checkpoints(const std::string& name);

/// The case's method at t = 0 at spacing dx (check_method first).
template <int D>
std::unique_ptr<Method<D>> make_method(const CaseSpec& spec, double dx);

/// The case's method continuing from the checkpoint file `path`, which must come from the same
/// case (parameters hash) and spacing; `run` receives the runner's bookkeeping stored with it.
/// Throws InputError if the method writes no checkpoints or the file is unreadable or foreign.
template <int D>
std::unique_ptr<Method<D>> resume_method(const CaseSpec& spec, double dx, const std::string& path, json& run);

}  // namespace sc
