// SPDX-License-Identifier: GPL-3.0-or-later
#include "app/misuse.hpp"

#include <iostream>
#include <string_view>
#include <vector>

#include "app/commands.hpp"
#include "common/did_you_mean.hpp"

namespace roifem::app {

namespace {

CLI::App* find_command(CLI::App& app, const std::string& name) {
  for (CLI::App* sub : app.get_subcommands({}))
    if (sub->get_name() == name) return sub;
  return nullptr;
}

}  // namespace

std::string find_misuse(CLI::App& app, int argc, const char* const* argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands({})) commands.push_back(sub->get_name());
  const std::string command = argv[1];
  CLI::App* sub = find_command(app, command);
  if (!sub) {
    std::string list;
    for (const auto& c : commands) list += (list.empty() ? "" : ", ") + c;
    return "unknown command '" + command + "'" + did_you_mean(command, commands) + " (commands: " + list + ")";
  }
  std::vector<std::string> options{"--help"};
  for (const CLI::Option* option : sub->get_options())
    for (const auto& name : option->get_lnames()) options.push_back("--" + name);
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--") break;  // what follows is positional
    if (!arg.starts_with("--")) continue;
    const std::string name(arg.substr(0, arg.find('=')));
    if (std::find(options.begin(), options.end(), name) != options.end()) continue;
    std::string message = "unknown option '";
    message.append(name).append("' for 'roifem ").append(command).append("'");
    message.append(did_you_mean(name, options)).append("; see roifem ").append(command).append(" --help");
    return message;
  }
  return "";
}

bool take_check_args(int& argc, char** argv) {
  if (argc < 2 || std::string_view(argv[1]) != "--check-args") return false;
  for (int i = 1; i + 1 < argc; ++i) argv[i] = argv[i + 1];
  argv[--argc] = nullptr;
  return true;
}

void add_help_command(CLI::App& app, Action& action) {
  auto command = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("help", "Print the help of roifem, or of one command: roifem help run");
  cmd->add_option("COMMAND", *command, "A command");
  cmd->callback([&app, &action, command] {
    action = [&app, command] {
      if (command->empty()) {
        std::cout << app.help();
        return;
      }
      CLI::App* sub = find_command(app, *command);
      if (!sub || sub->get_name() == "help") {
        std::vector<std::string> names;
        for (const CLI::App* s : app.get_subcommands({})) names.push_back(s->get_name());
        throw CLI::ValidationError("unknown command '" + *command + "'" + did_you_mean(*command, names));
      }
      std::cout << sub->help();
    };
  });
}

}  // namespace roifem::app
