"""The package's boundary: exceptions, input checks, atomic files, command-line helpers."""
