#pragma once
// What the CLI prints and writes about steps: JSON of a StepResult, table rows, contact rows, summaries.
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "framework/pipeline/step_result.hpp"

namespace ccdlab::cli {

/// Counters and per-phase milliseconds of one step.
nlohmann::json step_json(const StepResult& r);

/// The columns of steps.csv after step, frame_t0, frame_t1 (counters, phases, hash).
std::string csv_header();
std::string csv_row(const StepResult& r, std::uint64_t step_hash);

/// One contact as "vf,v,f0,f1,f2,toi" or "ee,a0,a1,b0,b1,toi" (vertex ids of the input mesh).
std::string contact_row(const Contact& c, const Positions& x_t0, const Positions& x_t1);
/// The columns of contact_row: kind, the four vertex ids, time of contact, the two coordinates (VF: barycentric
/// weights of f1, f2; EE: parameters on edge a, edge b) and the unit contact normal.
inline constexpr const char* kContactColumns = "kind,a,b,c,d,toi,u,v,nx,ny,nz";

/// Median of a list (0 for an empty list).
double median(std::vector<double> values);

/// Prints the human-readable per-step table: header once, then one row per step.
void print_table_header(std::FILE* out);
void print_table_row(std::FILE* out, const std::string& step, const StepResult& r);

/// A CSV field: as is, or quoted (doubled quotes inside) when it holds a comma, a quote or a newline.
std::string csv_field(const std::string& s);

/// The CPU's model name (/proc/cpuinfo), "unknown" elsewhere: result files say which machine measured them.
std::string cpu_model();

}  // namespace ccdlab::cli
