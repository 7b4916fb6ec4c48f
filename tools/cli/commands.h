// Subcommand registration for the `tessera` CLI: each file adds its subcommands to the app.
#pragma once

#include <CLI/CLI.hpp>

namespace tessera::cli {

void addRenderCommands(CLI::App& app);  // scenes, render, replay, validate (cmd_render.cpp)
void addDemoCommand(CLI::App& app);     // demo (cmd_demo.cpp)
void addGoldenCommands(CLI::App& app);  // golden check / update (cmd_golden.cpp)
void addVerifyCommands(CLI::App& app);  // crosscheck, visibility, compare, bench (cmd_verify.cpp)
void addMutantsCommand(CLI::App& app);  // mutants (cmd_mutants.cpp)
void addCityCommand(CLI::App& app);     // city (cmd_city.cpp)
void addMtaCommands(CLI::App& app);     // mta build / info (cmd_mta.cpp), then the three below
void addMtaRenderCommand(CLI::App* mtaCmd);  // mta render (cmd_mta_render.cpp)
void addMtaRunsCommand(CLI::App* mtaCmd);    // mta runs (cmd_mta_runs.cpp)
void addTexelCommand(CLI::App& app);         // texel (cmd_texel.cpp)
void addTabCommands(CLI::App& app);          // tab build / info / render (cmd_tab.cpp)
void addRttaCommands(CLI::App& app);         // rtta render / params (cmd_rtta.cpp)
void addSuiteCommands(CLI::App& app);        // suite run / merge (cmd_suite.cpp)

}  // namespace tessera::cli
