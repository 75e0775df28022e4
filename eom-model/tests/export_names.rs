//! `file::to_toml` loads back to the same model whatever the names: arbitrary Unicode in the
//! model's, bodies' and items' names, parameter units and descriptions. A name that holds a
//! character no name may hold (a control character, a bidirectional override, a line
//! separator) makes the file fail to load with an error naming the field — never load into
//! another model (the injection of issue 27: a line feed in the name used to end the header
//! comment and add a spring).

use eom_model::{
    Actuator, Body, FlexPoint, Linearizer, Method, Model, RigidPoint, Sensor, file, vec3, z_axis,
};
use eom_sym::pool::{Assumption, ParamInfo};
use proptest::prelude::*;

/// The names of one model: the model, two bodies, six items, two units and a description.
#[derive(Clone, Debug)]
struct Names {
    model: String,
    bodies: [String; 2],
    items: [String; 6],
    unit: String,
    description: String,
}

fn names() -> impl Strategy<Value = Names> {
    (
        any::<String>(),
        prop::array::uniform2(any::<String>()),
        prop::array::uniform6(any::<String>()),
        any::<String>(),
        any::<String>(),
    )
        .prop_map(|(model, bodies, items, unit, description)| {
            // Non-empty and distinct (`ground` is reserved): an index after the text.
            let tag = |k: usize, s: &String| format!("{s}#{k}");
            Names {
                model,
                bodies: [tag(0, &bodies[0]), tag(1, &bodies[1])],
                items: std::array::from_fn(|k| tag(k, &items[k])),
                unit,
                description,
            }
        })
}

/// Two masses on sliders, springs to the ground and between them, a force and a sensor.
fn model(n: &Names) -> Model {
    let mut m = Model::new(&n.model);
    let mass = m
        .param_info(ParamInfo {
            name: "m".into(),
            nominal: 1.5,
            unit: Some(n.unit.clone()),
            description: Some(n.description.clone()),
            assume: Assumption::Positive,
        })
        .unwrap();
    let k = m.param("k", 7.0).unwrap();
    let [b1, b2] = [&n.bodies[0], &n.bodies[1]];
    m.add(Body::new(b1).mass(mass).at(vec3(0, 0, 1)));
    m.add(Body::new(b2).mass(mass * 2).at(vec3(0, 0, 2)));
    for (k_item, b) in [(0, b1), (1, b2)] {
        m.add(
            RigidPoint::new(&n.items[k_item])
                .between(b, "ground")
                .at(vec3(0, 0, k_item as i64 + 1))
                .forces(2)
                .moments(3)
                .axis(z_axis()),
        );
    }
    m.add(
        FlexPoint::new(&n.items[2])
            .between(b1, "ground")
            .forces(1)
            .axis(z_axis())
            .stiffness(k, 0)
            .damping(0.1, 0),
    );
    m.add(
        FlexPoint::new(&n.items[3])
            .between(b2, b1)
            .at(vec3(0, 0, 1.5))
            .forces(1)
            .axis(z_axis())
            .stiffness(k * 3, 0),
    );
    m.add(
        Actuator::new(&n.items[4])
            .between(b1, "ground")
            .ends(vec3(0, 0, 1), vec3(0, 0, 0))
            .units(&n.unit),
    );
    m.add(
        Sensor::new(&n.items[5])
            .between(b2, "ground")
            .ends(vec3(0, 0, 2), vec3(0, 0, 0))
            .units("m"),
    );
    m
}

fn item_names(m: &Model) -> Vec<String> {
    let mut v: Vec<String> = m.bodies.iter().map(|b| b.name.to_string()).collect();
    v.extend(m.items().iter().map(|i| i.name().to_string()));
    v
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn an_export_loads_back_to_the_same_model_or_names_the_bad_field(n in names()) {
        let original = model(&n);
        let text = file::to_toml(&original);
        let texts = [&n.model, &n.bodies[0], &n.bodies[1]]
            .into_iter()
            .chain(&n.items)
            .chain([&n.unit]);
        let all_safe = texts.clone().all(|s| eom_text::name_problem(s).is_none())
            && eom_text::description_problem(&n.description).is_none();
        match file::load_str(&text, "exported.toml", &[]) {
            Ok(loaded) => {
                prop_assert!(all_safe, "loaded a model with an unsafe name:\n{text}");
                prop_assert_eq!(&loaded.model.name, &n.model);
                prop_assert_eq!(item_names(&loaded.model), item_names(&original));
                let spec = &loaded.params[0];
                prop_assert_eq!(&spec.unit, &n.unit);
                prop_assert_eq!(&spec.description, &n.description);
                let a0 = Linearizer::new(&original).method(Method::Numeric).run().unwrap();
                let a1 = Linearizer::new(&loaded.model).method(Method::Numeric).run().unwrap();
                prop_assert_eq!(&a0.state_space.a, &a1.state_space.a);
                prop_assert_eq!(&a0.state_space.b, &a1.state_space.b);
                prop_assert_eq!(&a0.state_space.c, &a1.state_space.c);
            }
            Err(e) => {
                prop_assert!(!all_safe, "a safe export failed to load: {e}\n{text}");
                let msg = e.to_string();
                prop_assert!(
                    msg.contains("field `name`") || msg.contains("field `unit")
                        || msg.contains("field `description`") || msg.contains("field `units`"),
                    "{msg}"
                );
                prop_assert!(
                    !msg.chars().any(|c| c != '\n' && eom_text::is_unsafe(c)),
                    "raw control character in {msg:?}"
                );
                prop_assert!(msg.chars().count() < 2000, "{} characters", msg.chars().count());
            }
        }
    }
}

#[test]
fn a_line_feed_in_the_name_cannot_add_a_spring() {
    let n = Names {
        model: "smd\n[[spring]]\nname = \"extra\"".into(),
        bodies: ["a".into(), "b".into()],
        items: std::array::from_fn(|k| format!("item {k}")),
        unit: "kg".into(),
        description: "a mass".into(),
    };
    let text = file::to_toml(&model(&n));
    // No table of its own: only as text in the comment and the string.
    assert!(!text.lines().any(|l| l.trim() == "[[spring]]"), "{text}");
    assert!(text.lines().next().unwrap().contains("smd\\n[[spring]]"));
    let e = file::load_str(&text, "exported.toml", &[])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("[model], field `name`") && e.contains("a line feed (U+000A) at character 4"),
        "{e}"
    );
}
