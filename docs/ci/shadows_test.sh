#!/bin/sh
# The sharded Bazel test of BUILD.bazel: one shard's verdict into the test's undeclared outputs
# (bazel-testlogs/<package>/shadows/shard_<k>_of_4/test.outputs/), which `shadowref merge` joins:
#   shadowref merge bazel-testlogs/<package>/shadows/shard_*_of_4/test.outputs/shadows --expectations shadows-expectations.txt --out shadows
# (with --nozip_undeclared_test_outputs; else unzip each outputs.zip first).
exec shadowref conform --candidate-dir renders --technique shadowmap --expectations shadows-expectations.txt \
    --out "$TEST_UNDECLARED_OUTPUTS_DIR/shadows"
