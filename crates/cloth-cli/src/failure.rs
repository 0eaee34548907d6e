//! What a subcommand that fails hands back: its message and the exit status it deserves
//! (2 when the input is at fault, 1 when a valid run fails).

/// A failure with the exit status it deserves.
pub struct Failure {
    pub message: String,
    pub status: u8,
}

impl Failure {
    pub fn input(message: impl std::fmt::Display) -> Self {
        Self {
            message: message.to_string(),
            status: 2,
        }
    }
    pub fn run(message: impl std::fmt::Display) -> Self {
        Self {
            message: message.to_string(),
            status: 1,
        }
    }
}
