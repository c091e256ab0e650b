int placeholder_terratin_progress_printer();
