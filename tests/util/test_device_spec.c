/* This file contains the test of the serial reference's device names
 * (util/device_spec.h). */
#include "testlib.h"
#include "util/device_spec.h"

int main(void)
{
    CHECK(tr_device_spec_is_reference("reference"));
    CHECK(tr_device_spec_is_reference("serial"));
    CHECK(tr_device_spec_is_reference("cpu-reference"));
    CHECK(!tr_device_spec_is_reference(NULL));
    CHECK(!tr_device_spec_is_reference(""));
    CHECK(!tr_device_spec_is_reference("auto"));
    CHECK(!tr_device_spec_is_reference("opencl"));
    CHECK(!tr_device_spec_is_reference("0:0"));
    CHECK(!tr_device_spec_is_reference("Reference")); /* specs are case sensitive */
    CHECK(!tr_device_spec_is_reference("reference "));
    CHECK(!tr_device_spec_is_reference("ref"));
    return tr_test_finish("test_device_spec");
}
