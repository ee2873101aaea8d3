//! Arithmetic expressions in a table family's parameters: `+ − × /`, integer powers,
//! parentheses, decimal constants and parameter names, as table files write a piece's
//! coefficients and breakpoints (`"1 - D/2"`, `"(w - 1)^2 / 4"`).
//!
//! An expression is parsed once, with its names resolved to the family's parameter
//! indices, and evaluated in any [`Number`] type: constants are kept as their decimal
//! text, so a number type wider than f64 reads them exactly (`0.1` is one tenth, not the
//! double nearest it), and every operation is the type's own. In f64 each operation
//! rounds once, in the order written (left to right, powers by repeated
//! multiplication), so the same text gives the same bits wherever it is evaluated.

pub use crate::real::Number;
use std::fmt;

/// The largest |exponent| of a power: enough for any polynomial coefficient, small
/// enough that evaluation is a handful of multiplications.
pub const MAX_POWER: i32 = 64;

/// The longest expression accepted, in characters.
pub const MAX_LENGTH: usize = 1000;

/// A parsed expression.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    text: String,
    root: Node,
}

#[derive(Clone, Debug, PartialEq)]
enum Node {
    Const(String),
    Param(usize),
    Neg(Box<Node>),
    Add(Box<Node>, Box<Node>),
    Sub(Box<Node>, Box<Node>),
    Mul(Box<Node>, Box<Node>),
    Div(Box<Node>, Box<Node>),
    Pow(Box<Node>, i32),
}

/// Why an expression was refused: the message and the 1-based character column.
#[derive(Clone, Debug, PartialEq)]
pub struct ExprError {
    /// What is wrong.
    pub message: String,
    /// Where (1-based, in characters).
    pub column: usize,
}

impl fmt::Display for ExprError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "at column {}: {}", self.column, self.message)
    }
}

impl Expr {
    /// Parse `text`, resolving names against `params` (exactly as spelled there).
    pub fn parse(text: &str, params: &[&str]) -> Result<Expr, ExprError> {
        let chars: Vec<char> = text.chars().collect();
        if chars.len() > MAX_LENGTH {
            return Err(ExprError {
                message: format!("{} characters: valid at most {MAX_LENGTH}", chars.len()),
                column: MAX_LENGTH + 1,
            });
        }
        let mut p = Parser {
            chars: &chars,
            at: 0,
            params,
            depth: 0,
        };
        let root = p.sum()?;
        p.skip_space();
        if p.at < chars.len() {
            return Err(p.error(format!(
                "unexpected '{}': expected an operator (+ - * / ^) or the end",
                chars[p.at]
            )));
        }
        Ok(Expr {
            text: text.trim().to_string(),
            root,
        })
    }

    /// A constant, from a number (written as the shortest decimal that reads back to it).
    pub fn constant(x: f64) -> Expr {
        let text = format!("{x:?}");
        Expr {
            root: Node::Const(text.clone()),
            text,
        }
    }

    /// The text it was parsed from (trimmed).
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Whether it uses no parameter.
    pub fn is_constant(&self) -> bool {
        !self.root.uses_param()
    }

    /// Whether it uses parameter `i`.
    pub fn uses(&self, i: usize) -> bool {
        self.root.uses(i)
    }

    /// The value in f64 with parameter `i` set to `values[i]`; None if a constant
    /// overflows to infinity.
    pub fn eval(&self, values: &[f64]) -> Option<f64> {
        self.root.eval(values, &())
    }

    /// The value in `N` at the precision of `ctx`, parameter `i` set to `values[i]`;
    /// None if a constant cannot be held by the type.
    pub fn eval_in<N: Number>(&self, values: &[N], ctx: &N::Context) -> Option<N> {
        self.root.eval(values, ctx)
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

impl Node {
    fn uses_param(&self) -> bool {
        match self {
            Node::Const(_) => false,
            Node::Param(_) => true,
            Node::Neg(a) | Node::Pow(a, _) => a.uses_param(),
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) | Node::Div(a, b) => {
                a.uses_param() || b.uses_param()
            }
        }
    }

    fn uses(&self, i: usize) -> bool {
        match self {
            Node::Const(_) => false,
            Node::Param(j) => *j == i,
            Node::Neg(a) | Node::Pow(a, _) => a.uses(i),
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) | Node::Div(a, b) => {
                a.uses(i) || b.uses(i)
            }
        }
    }

    fn eval<N: Number>(&self, values: &[N], ctx: &N::Context) -> Option<N> {
        Some(match self {
            Node::Const(t) => N::from_decimal(t, ctx)?,
            Node::Param(i) => values[*i].clone(),
            Node::Neg(a) => -a.eval(values, ctx)?,
            Node::Add(a, b) => a.eval(values, ctx)? + b.eval(values, ctx)?,
            Node::Sub(a, b) => a.eval(values, ctx)? - b.eval(values, ctx)?,
            Node::Mul(a, b) => a.eval(values, ctx)? * b.eval(values, ctx)?,
            Node::Div(a, b) => a.eval(values, ctx)? / b.eval(values, ctx)?,
            Node::Pow(a, n) => {
                let x = a.eval(values, ctx)?;
                let mut acc = N::one(ctx);
                for _ in 0..n.unsigned_abs() {
                    acc = acc * x.clone();
                }
                if *n < 0 {
                    N::one(ctx) / acc
                } else {
                    acc
                }
            }
        })
    }
}

/// Nesting deeper than this is refused (keeps the recursive parser's stack bounded).
const MAX_DEPTH: usize = 64;

struct Parser<'a> {
    chars: &'a [char],
    at: usize,
    params: &'a [&'a str],
    depth: usize,
}

impl Parser<'_> {
    fn error(&self, message: String) -> ExprError {
        ExprError {
            message,
            column: self.at + 1,
        }
    }

    fn skip_space(&mut self) {
        while self.at < self.chars.len() && self.chars[self.at].is_whitespace() {
            self.at += 1;
        }
    }

    fn peek(&mut self) -> Option<char> {
        self.skip_space();
        self.chars.get(self.at).copied()
    }

    // sum := product (('+' | '-') product)*
    fn sum(&mut self) -> Result<Node, ExprError> {
        let mut left = self.product()?;
        while let Some(op @ ('+' | '-')) = self.peek() {
            self.at += 1;
            let right = self.product()?;
            left = if op == '+' {
                Node::Add(Box::new(left), Box::new(right))
            } else {
                Node::Sub(Box::new(left), Box::new(right))
            };
        }
        Ok(left)
    }

    // product := unary (('*' | '/') unary)*
    fn product(&mut self) -> Result<Node, ExprError> {
        let mut left = self.unary()?;
        while let Some(op @ ('*' | '/' | '×')) = self.peek() {
            self.at += 1;
            let right = self.unary()?;
            left = if op == '/' {
                Node::Div(Box::new(left), Box::new(right))
            } else {
                Node::Mul(Box::new(left), Box::new(right))
            };
        }
        Ok(left)
    }

    // unary := ('-' | '+') unary | power
    fn unary(&mut self) -> Result<Node, ExprError> {
        match self.peek() {
            Some('-' | '−') => {
                self.at += 1;
                self.nested(|p| p.unary()).map(|a| Node::Neg(Box::new(a)))
            }
            Some('+') => {
                self.at += 1;
                self.nested(|p| p.unary())
            }
            _ => self.power(),
        }
    }

    // power := atom ('^' integer)?
    fn power(&mut self) -> Result<Node, ExprError> {
        let base = self.atom()?;
        if self.peek() != Some('^') {
            return Ok(base);
        }
        self.at += 1;
        self.skip_space();
        let start = self.at;
        let negative = matches!(self.chars.get(self.at), Some('-' | '−'));
        if negative {
            self.at += 1;
        }
        let digits_from = self.at;
        while self.at < self.chars.len() && self.chars[self.at].is_ascii_digit() {
            self.at += 1;
        }
        if self.at == digits_from || matches!(self.chars.get(self.at), Some('.' | 'e' | 'E')) {
            self.at = start;
            return Err(self.error("a power must be a whole number (e.g. x^2 or x^-1)".to_string()));
        }
        let digits: String = self.chars[digits_from..self.at].iter().collect();
        let n = digits
            .parse::<i32>()
            .ok()
            .filter(|n| *n <= MAX_POWER)
            .ok_or_else(|| ExprError {
                message: format!("power {digits}: valid -{MAX_POWER} to {MAX_POWER}"),
                column: start + 1,
            })?;
        if self.peek() == Some('^') {
            return Err(self.error("write x^a^b with parentheses".to_string()));
        }
        Ok(Node::Pow(Box::new(base), if negative { -n } else { n }))
    }

    // atom := number | name | '(' sum ')'
    fn atom(&mut self) -> Result<Node, ExprError> {
        match self.peek() {
            None => Err(self.error(
                "the expression ends here: expected a number, a parameter or '('".to_string(),
            )),
            Some('(') => {
                let open = self.at;
                self.at += 1;
                let inner = self.nested(|p| p.sum())?;
                if self.peek() != Some(')') {
                    return Err(ExprError {
                        message: "this '(' is not closed".to_string(),
                        column: open + 1,
                    });
                }
                self.at += 1;
                Ok(inner)
            }
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_alphabetic() || c == '_' => {
                let start = self.at;
                while self.at < self.chars.len()
                    && (self.chars[self.at].is_alphanumeric() || self.chars[self.at] == '_')
                {
                    self.at += 1;
                }
                let name: String = self.chars[start..self.at].iter().collect();
                match self.params.iter().position(|p| *p == name) {
                    Some(i) => Ok(Node::Param(i)),
                    None => Err(ExprError {
                        message: format!(
                            "unknown name '{name}': valid {}",
                            if self.params.is_empty() {
                                "numbers only (the file declares no [[param]])".to_string()
                            } else {
                                format!("the parameters {}", self.params.join(", "))
                            }
                        ),
                        column: start + 1,
                    }),
                }
            }
            Some(c) => Err(self.error(format!(
                "unexpected '{c}': expected a number, a parameter or '('"
            ))),
        }
    }

    fn number(&mut self) -> Result<Node, ExprError> {
        let start = self.at;
        let digits = |p: &mut Parser| {
            let from = p.at;
            while p.at < p.chars.len() && p.chars[p.at].is_ascii_digit() {
                p.at += 1;
            }
            p.at - from
        };
        let mut n = digits(self);
        if self.chars.get(self.at) == Some(&'.') {
            self.at += 1;
            n += digits(self);
        }
        if n == 0 {
            self.at = start;
            return Err(self.error("'.' is not a number".to_string()));
        }
        if matches!(self.chars.get(self.at), Some('e' | 'E')) {
            let mark = self.at;
            self.at += 1;
            if matches!(self.chars.get(self.at), Some('-' | '+')) {
                self.at += 1;
            }
            if digits(self) == 0 {
                self.at = mark;
                return Err(self.error("an exponent needs digits (e.g. 1e-3)".to_string()));
            }
        }
        let text: String = self.chars[start..self.at].iter().collect();
        if f64::from_decimal(&text, &()).is_none() {
            return Err(ExprError {
                message: format!("{text} is too large for a number"),
                column: start + 1,
            });
        }
        Ok(Node::Const(text))
    }

    fn nested(
        &mut self,
        f: impl FnOnce(&mut Self) -> Result<Node, ExprError>,
    ) -> Result<Node, ExprError> {
        if self.depth >= MAX_DEPTH {
            return Err(self.error(format!("nested more than {MAX_DEPTH} deep")));
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(text: &str, names: &[&str], values: &[f64]) -> f64 {
        Expr::parse(text, names).unwrap().eval(values).unwrap()
    }

    #[test]
    fn precedence_and_associativity_follow_arithmetic() {
        assert_eq!(eval("1 + 2 * 3", &[], &[]), 7.0);
        assert_eq!(eval("(1 + 2) * 3", &[], &[]), 9.0);
        assert_eq!(eval("8 / 4 / 2", &[], &[]), 1.0);
        assert_eq!(eval("10 - 4 - 3", &[], &[]), 3.0);
        assert_eq!(eval("-2^2", &[], &[]), -4.0);
        assert_eq!(eval("(-2)^3", &[], &[]), -8.0);
        assert_eq!(eval("2^-2", &[], &[]), 0.25);
        assert_eq!(eval("2 × 3", &[], &[]), 6.0);
        assert_eq!(eval("1.5e2", &[], &[]), 150.0);
        assert_eq!(eval(".5", &[], &[]), 0.5);
    }

    #[test]
    fn parameters_resolve_by_name() {
        let names = ["D", "w_2"];
        assert_eq!(eval("1 - D/2", &names, &[0.5, 0.0]), 0.75);
        assert_eq!(eval("w_2 * D", &names, &[3.0, 2.0]), 6.0);
        assert!(!Expr::parse("D", &names).unwrap().is_constant());
        assert!(Expr::parse("1 + w_2^2", &names).unwrap().uses(1));
        assert!(!Expr::parse("1 + w_2^2", &names).unwrap().uses(0));
        assert!(Expr::parse("2*3", &names).unwrap().is_constant());
    }

    #[test]
    fn each_operation_rounds_once_in_the_order_written() {
        // (1 − D/2) − D/2 is not 1 − D in floating point for every D; the written order
        // is kept.
        for d in [0.1, 0.3, 0.7, 1.0 / 3.0] {
            let half = 1.0 - d / 2.0;
            assert_eq!(
                eval("1 - D/2 - D/2", &["D"], &[d]).to_bits(),
                (half - d / 2.0).to_bits()
            );
            assert_eq!(eval("D^3", &["D"], &[d]).to_bits(), (d * d * d).to_bits());
        }
    }

    #[test]
    fn refusals_name_the_column() {
        let e = |t: &str| Expr::parse(t, &["D"]).unwrap_err();
        assert_eq!(e("1 +").column, 4);
        assert_eq!(e("2 * (D - 1").column, 5);
        assert_eq!(e("D * x").column, 5);
        assert!(e("D * x").message.contains("D"));
        assert_eq!(e("2 3").column, 3);
        assert_eq!(e("D^1.5").column, 3);
        assert_eq!(e("D^100").message, "power 100: valid -64 to 64");
        assert_eq!(e("1e").column, 2);
        assert_eq!(e("2 % 3").column, 3);
        assert!(e("1e999").message.contains("too large"));
        assert!(e(&"(".repeat(100)).message.contains("nested"));
        assert_eq!(e("D^2^2").column, 4);
        assert_eq!(e("").column, 1);
    }

    #[test]
    fn constants_keep_their_decimal_text() {
        // A wider number type sees the exact decimal; here a type that records it.
        #[derive(Clone, Debug, PartialEq)]
        struct Text(String);
        macro_rules! op {
            ($t:ident, $f:ident, $s:literal) => {
                impl std::ops::$t for Text {
                    type Output = Text;
                    fn $f(self, o: Text) -> Text {
                        Text(format!("({} {} {})", self.0, $s, o.0))
                    }
                }
            };
        }
        op!(Add, add, "+");
        op!(Sub, sub, "-");
        op!(Mul, mul, "*");
        op!(Div, div, "/");
        impl std::ops::Neg for Text {
            type Output = Text;
            fn neg(self) -> Text {
                Text(format!("-{}", self.0))
            }
        }
        impl Number for Text {
            type Context = ();
            fn from_decimal(t: &str, _: &()) -> Option<Text> {
                Some(Text(t.to_string()))
            }
            fn one(_: &()) -> Text {
                Text("1".into())
            }
        }
        let e = Expr::parse("0.1 * D - 2", &["D"]).unwrap();
        assert_eq!(
            e.eval_in(&[Text("d".into())], &()).unwrap().0,
            "((0.1 * d) - 2)"
        );
    }
}
