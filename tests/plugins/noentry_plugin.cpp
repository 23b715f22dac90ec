// A shared library that is not a slambox plugin (no entry point).
extern "C" __attribute__((visibility("default"))) int not_a_slambox_plugin() { return 42; }
