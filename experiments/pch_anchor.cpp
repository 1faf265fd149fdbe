// The source the experiment programs' precompiled header is built with (contact_experiment_pch,
// experiments/CMakeLists.txt): a program that does nothing, never installed or run.
int main() { return 0; }
