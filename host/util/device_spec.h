/* This file contains the names a device spec (--device, TIGHTROPE_DEVICE)
 * may give the serial reference, read the same way by every place that
 * takes a spec: the backend registry, the OpenCL device selection and bench. */
#ifndef TR_DEVICE_SPEC_H
#define TR_DEVICE_SPEC_H

/* Is spec one of the serial reference's names: "reference", "serial",
 * "cpu-reference"? NULL and "" are not (they mean the default). */
int tr_device_spec_is_reference(const char *spec);

#endif
