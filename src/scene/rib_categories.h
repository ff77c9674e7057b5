// What streyes does with each Option and Attribute value it is given (docs/SCENE-FORMAT.md, "Options
// and attributes"): every value is kept, as "category:name", in RenderSettings::options or
// Attributes::user, where the Shading Language's option() and attribute() and the features that
// read them find it; a value streyes does not use either only tunes another renderer (accepted
// silently) or changes what another renderer draws (warned once through Log::lenient: something
// the file asks for is missing from the picture). No option or attribute is an error because it is
// not declared: an undeclared name takes its type from its value (a float or a string).
#pragma once

#include <string>

#include "scene/rib_parser.h"

namespace streyes {

// Keeps every parameter of `params` as "category:name" in `into`; a name given again replaces its
// earlier value.
void keepCategoryValues(const std::string& category, const ParamList& params, ParamList& into);

// An Option that no request handler reads: silent when it only tunes another renderer, else warned
// once (Log::lenient).
void reviewOption(RibParser& reader, const std::string& category, const ParamList& params, const SourceLoc& loc);

// The same for an Attribute whose category streyes does not read (not identifier, light, user,
// streyes, displacementbound).
void reviewAttribute(RibParser& reader, const std::string& category, const ParamList& params, const SourceLoc& loc);

}  // namespace streyes
