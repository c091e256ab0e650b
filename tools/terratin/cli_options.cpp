int placeholder_terratin_cli_options();
