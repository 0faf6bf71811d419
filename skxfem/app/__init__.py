"""The applications: the command line, the reproduction of the paper's figures,
the grader and the course tooling, the result files."""
