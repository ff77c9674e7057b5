// What a scene may reach outside itself for: programs it runs, other files it reads, and where the
// files it asks to write may go. By default everything the user may do; `streyes render --safe`
// (for scenes from others: a render farm, a web service) refuses programs and plug-ins and keeps
// every file a scene writes inside one folder (docs/SCENE-FORMAT.md, "What a scene can do").
#pragma once

#include <string>

#include "streyes/error.h"

namespace streyes {

struct SceneAccess {
    bool programs = true;  // Procedural "RunProgram", and "DynamicLoad" of a plug-in from disk (a
                           // plug-in runs code as a program does; the built-in generators do not)
    bool files = true;     // ReadArchive and Procedural "DelayedReadArchive" of other files
    // Where the files a scene asks to write may go (checkSceneWrite): "" anywhere the user may
    // write; else only inside this folder, by relative names without "..".
    std::string writeFolder;
    bool safe = false;  // set by --safe: refusals name it and say what to do
};
void setSceneAccess(const SceneAccess& access);  // for the whole process
SceneAccess sceneAccess();

// The one check every request that writes a file makes before anything is written: Display,
// MakeTexture, MakeLatLongEnvironment (and MakeShadow, a shadow map's Display "zfile", the Shading
// Language's bake3d() as they come). `request` names it in the message ("Display"), `name` is the
// file as the scene gives it, `base` the folder a relative name is taken from ("" for the current
// folder; MakeTexture's is the RIB file's), `loc` where the scene asks. Without a write folder it
// returns; with one it throws InputError at `loc`, saying why and what to do, for an absolute name,
// a name with a ".." part, or a file that would not lie inside the folder once symbolic links are
// followed. Thread-safe (a shader may call it while buckets render).
void checkSceneWrite(const std::string& request, const std::string& name, const SourceLoc& loc,
                     const std::string& base = "");

}  // namespace streyes
