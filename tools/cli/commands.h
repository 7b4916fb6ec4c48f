// Subcommand registration for the `tessera` CLI: each file adds its subcommands to the app.
#pragma once

#include <CLI/CLI.hpp>

namespace tessera::cli {

void addRenderCommands(CLI::App& app);  // scenes, render, replay, validate (cmd_render.cpp)
void addDemoCommand(CLI::App& app);     // demo (cmd_demo.cpp)
void addGoldenCommands(CLI::App& app);  // golden check / update (cmd_golden.cpp)
void addVerifyCommands(CLI::App& app);  // crosscheck, visibility, compare, bench (cmd_verify.cpp)
void addCityCommand(CLI::App& app);     // city (cmd_city.cpp)
void addMtaCommands(CLI::App& app);     // mta build / info (cmd_mta.cpp)
// mta render / runs and the top-level texel (cmd_mta_render.cpp)
void addMtaRenderCommands(CLI::App& app, CLI::App* mtaCmd);

}  // namespace tessera::cli
