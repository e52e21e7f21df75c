/*
 * fmu_common.h -- what every native anvilwave FMU shares: strings, the resources folder of
 * fmuResourceLocation, and the reader of the text resource "anvilwave-unit", which holds what
 * a build makes particular for the generic binaries (Ram, PileSoil, Anvil / AnvilLumped).
 *
 * The text resource (resources/anvilwave_unit.txt), ASCII, whitespace-separated tokens:
 *
 *     anvilwave-unit 1            magic and format version
 *     kind <kind>                 the model identifier (Ram, PileSoil, Anvil, AnvilLumped): it
 *                                 picks the model (variable table) among the binary's
 *     guid <guid>                 the GUID of modelDescription.xml (FMI 3.0: the
 *                                 instantiationToken)
 *     start <name> <value>        the start value of a Real parameter, or of a Boolean one as 0
 *                                 or 1 (any number of lines; a parameter without one keeps the
 *                                 default of the binary's variable table)
 *     array <name> <n> <v1> ... <vn>   a named array of n Reals (any number of lines)
 *     end
 *
 * Reals are written as C99 hexadecimal floating constants (Python float.hex(), e.g.
 * 0x1.3a5p+3), read exactly on every platform. Lines starting with # are comments. The
 * anvils have no arrays: the ROM's modes are the binary modal-data resource named by its
 * String parameter modal_data_file (anvil_model.h), whose start value is the table's
 * "modal_data.bin".
 */
#ifndef FMU_COMMON_H
#define FMU_COMMON_H

#include <stddef.h>

#define FMU_MESSAGE_SIZE 2048
#define FMU_MAX_STEP 1.0e3
/* Largest communication step of the native units [s]: a blow lasts tens of milliseconds; a
 * step of more than 1000 s is a master's mistake (and one of 1e300 s would overflow the
 * states or, in the modal recurrences, give meaningless phases). */
#define FMU_UNIT_MAGIC "anvilwave-unit"
#define FMU_UNIT_VERSION 1
#define FMU_UNIT_RESOURCE "anvilwave_unit.txt"

/* A malloc'ed copy of text (NULL when out of memory). */
char *fmu_copy_string(const char *text);

/* The resources folder of fmuResourceLocation (file:///path, file:/path,
 * file://localhost/path; percent-encoded), without a trailing slash; "" when there is none or
 * it is not a local file URI; NULL when out of memory. */
char *fmu_resource_folder(const char *uri);

/* Whether path is absolute (POSIX or Windows). */
int fmu_is_absolute(const char *path);

/* folder/name, malloc'ed (NULL when out of memory). */
char *fmu_join(const char *folder, const char *name);

/* ------------------------------------------------------------------ text resource */
typedef struct {
    char *name;
    size_t size;
    double *values;
} FmuArray;

typedef struct {
    char kind[64];
    char guid[128];
    size_t n_starts;
    char **start_names;
    double *start_values;
    size_t n_arrays;
    FmuArray *arrays;
} FmuResource;

/* Read and parse a text resource; 0 with the reason on failure (res is then empty). */
int fmu_resource_read(const char *path, FmuResource *res, char *reason, size_t reason_size);

void fmu_resource_free(FmuResource *res);

/* The array of that name (NULL when absent); *size its length. */
const double *fmu_resource_array(const FmuResource *res, const char *name, size_t *size);

/* The start value of that parameter in *value; 0 when absent. */
int fmu_resource_start(const FmuResource *res, const char *name, double *value);

#endif /* FMU_COMMON_H */
