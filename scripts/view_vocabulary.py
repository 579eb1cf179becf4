#!/usr/bin/env python3
"""Writes src/model/view_commands.txt: every Adams View command and its
parameters, from which `src/model/view_vocabulary.rs` resolves View's
abbreviations (`part cre rig name_and_position part_name = ... loc = ...`).

The source is the list of View commands and parameters gathered from the
Adams View command reference by the adams_vscode project
(https://github.com/bthornton191/adams_vscode, MIT licence), file
`resources/adams_view_commands/structured.json` (read at commit ac8909d),
and the command language's own commands, which that list leaves out
(`for`, `while`, `if` ... from View's "Command Language" reference).

Usage: python3 scripts/view_vocabulary.py structured.json > src/model/view_commands.txt
"""

import json
import sys

# The command language's commands and their parameters (View reference,
# "Command Language Statements"): not in the command list above.
LANGUAGE = {
    "for": ["variable_name", "object_names", "type_filter", "start_value",
            "end_value", "increment_value", "group_name", "echo_all_loops"],
    "while": ["condition", "echo_all_loops"],
    "if": ["condition"],
    "elseif": ["condition"],
    "else": [],
    "end": [],
    "break": [],
    "continue": [],
    "return": [],
}

# View's other top-level commands the list leaves out (View reference,
# "Commands"), so that an abbreviation is unique among all View's commands.
OTHERS = {
    "abort": ["stop_all_commands"],
    "exit": ["confirmation"],
    "help": ["command_or_topic", "context_sensitive", "tips"],
    "info_window close": [],
    "info_window empty": [],
    "info_window read": ["file_name", "word_wrap"],
    "language switch_to python": [],
    "pause": ["time_delay", "alert"],
    "plugin load": ["plugin_name"],
    "plugin unload": ["plugin_name"],
    "quit": ["confirmation"],
    "reset": [],
    "snapshot": [],
    "stereo": ["active"],
    "stop": ["confirmation"],
    "symmetry_relation attributes": ["symmetry_relation_name", "scale_of_icons",
                                     "size_of_icons", "visibility", "name_visibility",
                                     "color", "active", "dependents_active"],
    "symmetry_relation copy": ["symmetry_relation_name", "new_symmetry_relation_name"],
    "symmetry_relation create": ["symmetry_relation_name", "updaters", "command", "comments"],
    "symmetry_relation delete": ["symmetry_relation_name"],
    "symmetry_relation modify": ["symmetry_relation_name", "new_symmetry_relation_name",
                                 "updaters", "remove_updaters", "add_updaters", "command",
                                 "comments"],
    "system": ["command_text", "send_output_to_info_window", "echo_to_logfile"],
    "time animations": ["enabled"],
    "time commands": ["enabled"],
    "time generic report": [],
    "time generic reset": [],
    "undo backward": [],
    "undo begin_block": ["suppress"],
    "undo end_block": [],
    "undo flush": [],
    "undo forward": [],
    "undo set": ["steps_stored"],
}


def main():
    with open(sys.argv[1], encoding="utf-8") as source:
        commands = json.load(source)
    for name, parameters in list(LANGUAGE.items()) + list(OTHERS.items()):
        commands.setdefault(name, parameters)
    print("# Adams View's commands and their parameters, one command a line:")
    print("# `words: parameters`. Written by scripts/view_vocabulary.py; do not edit.")
    for name in sorted(commands):
        words = name.split()
        if not words or any(not w.replace("_", "").isalnum() for w in words):
            continue
        seen = []
        for parameter in commands[name]:
            if parameter not in seen:
                seen.append(parameter)
        print(f"{' '.join(words)}: {' '.join(seen)}".rstrip())


if __name__ == "__main__":
    main()
