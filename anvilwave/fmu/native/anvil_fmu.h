/*
 * anvil_fmu.h -- the variables of the native Anvil / AnvilLumped FMUs.
 *
 * anvil_fmu.c works on slots (AnvilSlot); the build (fmu/native_build.py) writes
 * anvil_config.h, which maps each FMI value reference onto a slot with its type, causality and
 * start value (ANVIL_VARIABLES), and names the model (ANVIL_MODEL_IDENTIFIER, ANVIL_GUID,
 * ANVIL_LUMPED). The same table is written into modelDescription.xml, so the two agree.
 */
#ifndef ANVIL_FMU_H
#define ANVIL_FMU_H

#include "fmi2TypesPlatform.h"

typedef enum {
    /* parameters of the ROM anvil */
    ANVIL_MODAL_DATA_FILE,
    ANVIL_FMAX,
    ANVIL_DAMPING_RATIO,
    ANVIL_STATIC_CORRECTION,
    /* parameter of the lumped anvil */
    ANVIL_MASS,
    /* parameters of both */
    ANVIL_RAM_CONTACT_STIFFNESS,
    ANVIL_PILE_CONTACT_STIFFNESS,
    ANVIL_RAM_CONTACT_DAMPING,
    ANVIL_PILE_CONTACT_DAMPING,
    ANVIL_GRAVITY,
    ANVIL_START_AT_REST,
    ANVIL_INITIAL_PILE_HEAD_DISPLACEMENT,
    ANVIL_INPUT_EXTRAPOLATION,
    /* inputs */
    ANVIL_U_RAM,
    ANVIL_V_RAM,
    ANVIL_U_PILE,
    ANVIL_V_PILE,
    /* outputs */
    ANVIL_F_RAM,
    ANVIL_F_PILE,
    ANVIL_U_TOP,
    ANVIL_U_BOTTOM,
    ANVIL_N_SLOTS
} AnvilSlot;

typedef enum { ANVIL_REAL, ANVIL_BOOLEAN, ANVIL_STRING } AnvilType;

typedef enum { ANVIL_PARAMETER, ANVIL_INPUT, ANVIL_OUTPUT } AnvilCausality;

typedef struct {
    fmi2ValueReference vr;
    AnvilType type;
    AnvilCausality causality;
    AnvilSlot slot;
    const char *name;
    double real_start;        /* Real parameters and inputs */
    int boolean_start;        /* Boolean parameters */
    const char *string_start; /* String parameters */
} AnvilVariable;

#endif /* ANVIL_FMU_H */
