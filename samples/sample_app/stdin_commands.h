#pragma once

namespace physhand::sample {

// What a user at a headset asks for, one line on standard input each: `r` resets the
// scene, `n` goes on to the next scene file, `q` quits.
enum class UserCommand { None, Reset, Next, Quit };

// The next command typed, without blocking; None when nothing (or nothing known) was typed.
// An end of input (stdin from /dev/null, say) asks for nothing.
UserCommand poll_user_command();

}  // namespace physhand::sample
