/* What every definition struct of the host libraries shares
 * (docs/conventions.md, "Definitions").
 *
 * A definition (mr_world_def, mr_glove_def, mr_stage_def, ...) is made by
 * its default maker, mr_default_x_def(), and then changed field by field.
 * Its first field is `uint32_t cookie`, which the maker sets to
 * MR_DEF_COOKIE and the call that takes the definition checks: a struct
 * filled by hand ({0}, memset) is refused with a message instead of
 * running with zeros where a later field has a non-zero default. Never set
 * the cookie by hand. */
#ifndef MR_DEF_H
#define MR_DEF_H

#ifdef __cplusplus
extern "C" {
#endif

#define MR_DEF_COOKIE 0x6d724466u /* "mrDf" */

#ifdef __cplusplus
}
#endif

#endif /* MR_DEF_H */
