"""One curve: accuracy presets → discretisation → solve (with error estimate) → result files."""
